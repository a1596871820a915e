"""`python -m mf_envs.cli ...`: the same as the `mf-envs` command."""

import sys

from mf_envs.cli import main

sys.exit(main())
