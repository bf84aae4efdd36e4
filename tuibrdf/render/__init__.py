"""Terminal pictures: arrays in, Rich renderables and plain strings out (never imports textual)."""
