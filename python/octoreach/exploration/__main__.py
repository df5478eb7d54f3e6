"""``python -m octoreach.exploration --scene 2 --out DIR``: the exploration demo."""
from .demo import main

raise SystemExit(main())
