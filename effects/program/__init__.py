"""What a lowered pass is: the IR (one op table), the PassProgram, and the back-end
protocol and registry. What the back ends may import of `effects`, with `effects.base`."""
