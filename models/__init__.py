"""Ready mechanisms built with exuclear: the library's scenes, installed as ``exuclear.models``.

Each scene is a module with a parameter dataclass (``*Params``, the paper's or the
documented values in a named constructor), ``build(params) -> Scene``
(:class:`~exuclear.models.scene.Scene`), ``default_settings(params)``, ``run`` and a
command line, ``python -m exuclear.models.NAME --help``: ``journal_bearing``,
``slider_crank``, ``four_bar``, ``misaligned_shaft``, ``guided_slider_crank``.  ``journal_bearing``,
``slider_crank`` and ``guided_slider_crank`` are also studies of the study runner (``python -m
exuclear.study slider-crank``), declared to it as entry points in ``pyproject.toml``.

The scenes use the library's public API; the library never imports them.
"""
