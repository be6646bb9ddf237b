"""Physical constants shared by every model and reader."""

#: standard gravity [m/s²]: the default g of every model and the value of the unit "g"
STANDARD_GRAVITY = 9.80665
