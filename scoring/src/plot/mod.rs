//! Figures in the style of the POMDAR paper: radar plots per embodiment set and overall score
//! against degrees of freedom, as SVG text and PNG bytes (being written for issue 7).
