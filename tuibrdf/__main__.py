import sys

from tuibrdf.cli import main

sys.exit(main())
