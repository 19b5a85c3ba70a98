"""Tests of the check stage (xacrokit.check), one module per part of it."""
