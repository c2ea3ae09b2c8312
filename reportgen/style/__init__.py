"""Typography shared by scenes and the report: the one number formatter, the fonts, the
matplotlib style.  Depends on nothing else in reportgen."""
