//! PDDL front end: lexer with byte spans, parser, AST, errors with `file:line:col`.
