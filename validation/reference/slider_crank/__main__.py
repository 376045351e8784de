"""``python -m validation.reference.slider_crank``."""
import sys

from validation.reference.slider_crank.cli import main

sys.exit(main())
