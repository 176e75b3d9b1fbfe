"""``python -m kinematica``: the command line, as the ``kinematica`` script runs it."""

import sys

from kinematica.cli.main import main

sys.exit(main())
