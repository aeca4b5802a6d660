"""Research studies of rubbercontact and the validation behind VALIDATION.md.

Not part of the library: each ``studies/<name>.py`` is one study, run through
``python -m studies <name> [args]`` (studies/README.md states the convention). Their reports
live in ``docs/validation/``.
"""
