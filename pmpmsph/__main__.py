"""`python -m pmpmsph ...`: parse arguments, set up logging, run. Nothing else lives here."""
import sys

from .cli import main

sys.exit(main())
