"""The backend's tests.

The app answers only to the host names it is meant to be reached by (api/request_origin.py);
the test client calls it "testserver". Set here, before any test builds its Settings.
"""

import os

os.environ.setdefault("HOLISCENE_ALLOWED_HOSTS", '["testserver"]')
