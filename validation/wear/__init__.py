"""The wear scripts: the worn-in journal against its law (:mod:`.worn_in_journal`) and the
paper's slider-crank after many revolutions (:mod:`.slider_crank`)."""
