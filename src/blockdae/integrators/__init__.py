"""Model-agnostic integrators for the hybrid driver: CVODE, IDA (a model's DAE form)
and diffrax (the JAX twin); no physics here."""
