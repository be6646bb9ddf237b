"""Model-agnostic numerical pieces shared by the driver and the compiled engines."""
