"""``python -m validation.cost NAME [options]``: run one cost, timing or step-accuracy script."""
import sys

from validation.cost import main

sys.exit(main())
