"""FloatingGOWEC-v0: the gyroscopic wave energy converter as it floats (`env.GOWECV1Env`)."""
