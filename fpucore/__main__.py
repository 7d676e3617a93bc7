import sys

from fpucore.cli import main

sys.exit(main())
