"""A mass on a compliant support that can leave the ground (Newmark 1969): the supports,
the spring-supported mass, its solution and flights, the paper's estimates."""

from ._model import SpringDAEForm, SpringSupportedMass
from ._modes import UpthrowMode
from ._solution import Flight, UpthrowEvent, UpthrowSolution
from ._support import RigidSupport, SpringSupport
from ._estimate import UpthrowEstimate, upthrow_estimate

__all__ = ["Flight", "RigidSupport", "SpringDAEForm", "SpringSupport", "SpringSupportedMass", "UpthrowEstimate",
           "UpthrowEvent", "UpthrowMode", "UpthrowSolution", "upthrow_estimate"]

# what the other packages of blockdae use
from ._support import parse_support
