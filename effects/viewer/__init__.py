"""The viewer: window, panel, state, drawing, hot reload."""
