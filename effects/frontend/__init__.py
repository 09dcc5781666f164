"""The front end: .fx text to the Effect model (preprocessor, lexer, lark grammar, parser, printer)."""
