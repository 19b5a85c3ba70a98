"""Data folder shipped with xacrokit (found through importlib.resources); holds no code."""
