"""``python -m validation.slider_crank``."""
import sys

from validation.slider_crank.cli import main

sys.exit(main())
