"""Teaching material: traced algorithms and animations of them (``voroforge explain``)."""
