"""``python -m validation.hard_cases``."""
import sys

from validation.hard_cases.cli import main

sys.exit(main())
