"""The model-adequacy part of ``betv check``'s view: its JSON (:class:`AdequacyOut`, a
field of :class:`betvdesign.checks.view.SetOut`) and its line in the compact block.

Built from a set check's ``adequacy``
(:class:`betvdesign.checks.adequacy_data.SetAdequacy`, via its ``as_dict``), which is
None when the check did not assess it.
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field


class AdequacyPointOut(BaseModel):
    """One exact periodic orbit of the adequacy study."""

    model_config = ConfigDict(extra="forbid")

    quality_normal: float | None = Field(description="Q_v [-]; null: undamped")
    quality_tangential: float | None = Field(description="Q_h [-]; null: undamped")
    restitution: float = Field(description="e [-]")
    status: str = Field(description="periodic solver status")
    mode: str | None = Field(description="push, pull, stalled, none (not driven) or null")
    delta_s: float | None = Field(description="periodic slider increment per cycle [-]")
    speed_m_s: float | None = Field(description="signed mean speed along the impacts [m/s]")


class AdequacyOut(BaseModel):
    """Is the paper's idealised model (undamped, plastic impacts) adequate for this set?"""

    model_config = ConfigDict(extra="forbid")

    status: Literal[
        "adequate", "flips-beyond", "speed-differs", "mode-flips", "ideal-fails", "failed"
    ]
    adequate: bool = Field(description="the idealised model's mode holds")
    summary: str
    message: str
    source: Literal["device", "default"] = Field(
        description="damping/restitution from the device file, or the plausible defaults"
    )
    reference_mode: str | None
    ideal: AdequacyPointOut
    richer: AdequacyPointOut
    speed_change: float | None = Field(description="(v_richer − v_ideal)/v_ideal [-]")
    flip_quality: float | None = Field(description="Q at which the mode first flips [-]")
    flip_restitution: float | None = Field(description="e at which the mode first flips [-]")
    crossings: list[dict[str, Any]] = Field(description="every change of mode found")
    quality_range: list[float]
    restitution_range: list[float]


def adequacy_out(sc: Any) -> AdequacyOut | None:
    """The JSON of a set check's adequacy (None when not assessed)."""
    a = getattr(sc, "adequacy", None)
    return None if a is None else AdequacyOut.model_validate(a.as_dict())


def adequacy_line(sc: Any) -> str | None:
    """``model adequacy: <status>: <summary>`` for the compact block when the idealised
    model is adequate (an info rule, not listed otherwise); None when not assessed or
    not adequate (then the warning ``model-adequacy`` says it, once for mirrored sets)."""
    a = getattr(sc, "adequacy", None)
    return None if a is None or not a.adequate else a.line()
