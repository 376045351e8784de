"""``python -m validation.cross_check``."""
import sys

from validation.cross_check.cli import main

sys.exit(main())
