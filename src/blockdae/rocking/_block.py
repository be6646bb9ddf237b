"""What both free-standing blocks are (Housner's :class:`RockingBlock` and the complete
:class:`FreeStandingBlock`): a uniform rectangular block 2b wide and 2h high [m] with base
friction mu (mu_kinetic while it slips) [-], released from a tilt theta0 [rad], on a base
that accelerates by a_x(t) and a_z(t) [m/s²]; its field checks, geometry, batches of
parameter sets and how it reads its motion, written once."""

import dataclasses
import math

import numpy as np

from ..core import set_batch_fields, set_real_fields
from ..core.contract import BatchedModel
from ..excitation import AbstractExcitation, BaseMotion, Pieces
from ._modes import BEYOND, IN, OUT


#: a rotation rate below RATE_FLOOR p alpha [rad/s] (a slip below RATE_FLOOR p R [m/s]) is
#: no contradiction of its mode
RATE_FLOOR = 1e-10
#: the fields of both blocks
SHARED_FIELDS = ("b", "h", "mu", "mu_kinetic", "theta0", "zeno_arc", "g")
#: the options of Housner's block alone (``contact="housner"``)
HOUSNER_OPTIONS = {"restitution", "p", "linearised", "strict"}
#: contact -> the model of a block with that contact, as each is defined
MODELS = {}


def model_of(contact: str):
    """The model of a free-standing block with ``contact`` ("complete": its pivot may slip
    and lift; "housner": it holds); ValueError naming the contact otherwise."""
    if contact not in MODELS:
        raise ValueError(f"contact={contact!r} must be 'complete' (the pivot may slip and lift) or 'housner' (it "
                         "holds: Housner's block)")
    return MODELS[contact]


class BlockBase(BatchedModel):
    """The fields b, h [m], mu, mu_kinetic [-], theta0 [rad], zeno_arc [s] and g [m/s²]
    checked, alpha and R, batches, the motion (a_x, a_z) and ``replace`` across contacts,
    for a frozen dataclass that declares them and its ``contact`` ("complete" or
    "housner": the one model of each, :func:`model_of`)."""

    #: the parameters a batch may give as 1-D arrays, one value per parameter set
    batch_fields: tuple = ("b", "h", "mu", "mu_kinetic", "theta0")
    #: the optional batch fields: None (their default) or a number [their units]
    optional_fields: tuple = ("mu_kinetic",)

    def __init_subclass__(cls, **kwargs):
        """A block with a ``contact`` of its own is that contact's model (:func:`model_of`)."""
        super().__init_subclass__(**kwargs)
        if "contact" in vars(cls):
            MODELS[cls.contact] = cls

    parameter_labels = {"b": "half-width b [m]", "h": "half-height h [m]", "mu": "static friction coefficient mu [-]",
                        "mu_kinetic": "kinetic friction coefficient [-]", "restitution": "restitution r [-]",
                        "p": "frequency parameter p [rad/s]", "theta0": "initial tilt theta0 [rad]"}

    def _check_fields(self) -> bool:
        """Check the shared fields of one parameter set (ValueError naming the field and
        its value), setting each to a float; False for a batch, which is checked set by set
        (:meth:`_check_batch`) instead."""
        if any(np.ndim(getattr(self, name)) for name in self.batch_fields):
            self._check_batch()
            return False
        set_real_fields(self, ("b", "h", "mu", "theta0", "zeno_arc", "g"))
        for name in ("b", "h", "g", "zeno_arc"):
            if getattr(self, name) <= 0:
                raise ValueError(f"{name}={getattr(self, name)!r} must be > 0")
        if self.mu < 0:
            raise ValueError(f"mu={self.mu!r} must be >= 0")
        set_real_fields(self, tuple(name for name in self.optional_fields if getattr(self, name) is not None))
        if self.mu_kinetic is not None and not 0 <= self.mu_kinetic <= self.mu:
            raise ValueError(f"mu_kinetic={self.mu_kinetic!r} must be in [0, mu={self.mu}] (kinetic friction "
                             "cannot exceed static friction)")
        if not abs(self.theta0) < math.pi / 2:
            raise ValueError(f"theta0={self.theta0!r} must be in (-pi/2, pi/2) [rad]")
        return True

    def _check_batch(self) -> None:
        """A batch: the array fields set to read-only 1-D arrays of one size [their units],
        each parameter set checked as a block of its own (ValueError naming the set)."""
        shape = set_batch_fields(self, tuple(name for name in self.batch_fields if getattr(self, name) is not None))
        set_real_fields(self, ("zeno_arc", "g"))
        object.__setattr__(self, "_batch_shape", shape)
        for j in range(shape[0]):
            try:
                self.item(j)
            except ValueError as error:
                raise ValueError(f"parameter set {j}: {error}") from None

    # ---- what the block is ----------------------------------------------------------
    @property
    def alpha(self):
        """Slenderness atan(b/h) [rad]."""
        return math.atan2(self.b, self.h)

    @property
    def R(self):
        """Distance from a base corner to the centre of mass [m]."""
        return math.hypot(self.b, self.h)

    @property
    def slenderness_ratio(self):
        """lambda = b/h = tan(alpha) [-]: |a_x|/g_e that tips the block from rest."""
        return self.b / self.h

    @property
    def friction_kinetic(self):
        """Kinetic friction coefficient [-] (mu unless given)."""
        return self.mu if self.mu_kinetic is None else self.mu_kinetic

    def rotation_contradiction(self, kind, s, theta_rate, velocity_error):
        """A rocking rotation (|mode| ``kind``, side ``s``) whose rate ``theta_rate``
        [rad/s] points against its mode beyond the velocity error and beyond 1e-10 p alpha
        [rad/s] (an apex that grazes zero where a(t) turns at a sample dips below it by the
        integrator's error): its message, else None."""
        velocity_error = max(velocity_error, RATE_FLOOR * self.frequency * self.alpha)
        if kind in (OUT, BEYOND) and s * theta_rate < -velocity_error:
            return f"theta' = {theta_rate:+.6g} rad/s points toward the base"
        if kind == IN and s * theta_rate > velocity_error:
            return f"theta' = {theta_rate:+.6g} rad/s points away from the base"
        return None

    def replace(self, **changes):
        """A copy with some parameters changed (validated again); ``contact=`` another
        contact gives the other model of the same block (b, h, mu, mu_kinetic, theta0,
        zeno_arc, g), where Housner's options (restitution, p, linearised, strict) are
        left at their defaults."""
        contact = changes.pop("contact", self.contact)
        if contact == self.contact:
            return dataclasses.replace(self, **changes)
        given = sorted(name for name in HOUSNER_OPTIONS if getattr(self, name, None) is not None
                       and getattr(self, name) is not False)
        if given and contact == "complete":
            raise ValueError(f"contact='complete': {', '.join(given)} belongs to Housner's block only (the complete "
                             "block has none)")
        return model_of(contact)(**{**{name: getattr(self, name) for name in SHARED_FIELDS}, **changes})

    # ---- a batch of parameter sets ----------------------------------------------------
    @property
    def batch_shape(self) -> tuple[int, ...]:
        """() for one parameter set, (n,) for a batch of n."""
        return self.__dict__.get("_batch_shape", ())

    def item(self, index: int):
        """Parameter set ``index`` of a batch, as a block of its own (the parameters given
        as numbers as they were given)."""
        return dataclasses.replace(self, **{name: float(getattr(self, name)[index]) for name in self.batch_fields
                                             if isinstance(getattr(self, name), np.ndarray)})

    def batch_parameters(self) -> dict:
        """The grid: each batch field given (b, h [m], mu [-], ... in
        :attr:`parameter_labels`' units), of shape ``batch_shape``."""
        return {name: np.broadcast_to(np.asarray(getattr(self, name), dtype=float), self.batch_shape)
                for name in self.batch_fields if getattr(self, name) is not None}

    # ---- the motion -----------------------------------------------------------------
    def check_motion(self, motion) -> None:
        """An excitation (a_x) or a :class:`~blockdae.BaseMotion` with x and z components."""
        if isinstance(motion, BaseMotion):
            if motion.y is not None:
                raise ValueError("a free-standing block moves in the x-z plane: its BaseMotion takes no y component")
            return
        if not isinstance(motion, AbstractExcitation):
            raise TypeError(f"motion must be an excitation (Harmonic, Record, ...) or a BaseMotion, "
                            f"got {type(motion).__name__}")
        super().check_motion(motion)

    def excitation_pieces(self, excitation, t_end):
        """(a_x, a_z) pieces on one partition of [0, t_end] [s] (a_x's own, a_z = 0, for
        a horizontal excitation alone)."""
        if not isinstance(excitation, BaseMotion):
            ax = excitation.pieces(t_end)
            return ax, Pieces.linear(ax.t0, ax.h, 0.0, 0.0)
        ax, _, az = excitation.aligned_pieces(t_end)
        return ax, az

    def _base(self, t, excitation):
        """(a_x [m/s²], g_e = g + a_z [m/s²], a_x' [m/s³], a_z' [m/s³]) at ``t`` [s]."""
        return (excitation.component(0, t), self.g + excitation.component(1, t),
                excitation.component_rate(0, t), excitation.component_rate(1, t))
