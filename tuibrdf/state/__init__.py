"""The viewer's state as plain Python (no Textual): :mod:`.viewer` holds every transition a key
makes, :mod:`.presets` saves and loads named looks.  The CLI and the app both use it."""
