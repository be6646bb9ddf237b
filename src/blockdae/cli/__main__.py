"""``python -m blockdae.cli``: the ``blockdae`` command."""

import sys

from ._main import main

sys.exit(main())
