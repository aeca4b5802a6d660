"""Tests of the studies' own code (runner, templates, report text); the package's tests
are in tests/ and import only the package."""
