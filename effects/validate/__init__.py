"""Validation: a technique against a caps profile, with every reason; selection."""
