"""Applications on top of the stack: the demo, scenario runs and their evaluation, run pictures, the operator
command-line tool. They start nodes as processes (:mod:`flex_nav.testing.process`); nothing imports them."""
