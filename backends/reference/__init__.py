"""The NumPy reference back end: the ground truth the GL back end is compared against."""
