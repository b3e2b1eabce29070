"""`python -m holiscene.cli`: the `holiscene` command without its console script."""

from . import main

raise SystemExit(main())
