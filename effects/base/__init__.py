"""The ground floor: errors and locations, limits on untrusted input, reading untrusted
files and YAML, and the caches' storage. Imports nothing else of `effects`."""
