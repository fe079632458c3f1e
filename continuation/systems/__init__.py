"""Curve systems ``G(z) = 0`` (the contract, :class:`CurveSystem`): the ordinary branch, the
fold curve's minimally augmented system, and the Newton corrector on them."""
