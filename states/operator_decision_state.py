"""OperatorDecisionState: offer the operator a choice of outcomes, with a suggestion the engine may take."""

from __future__ import annotations

from typing import Optional, Sequence

from flex_nav.behavior.state import State
from flex_nav.behavior.userdata import UserDataView
from flex_nav.exceptions import ConfigError, choices_message
from flex_nav_states import validation


class OperatorDecisionState(State):
    """Offers a decision (yes/no/...) with a suggested outcome; the autonomy of each transition decides who answers.

    The state returns its ``suggestion`` at once. The behavior engine fires it by itself when the
    transition's required autonomy is below the current one (e.g. ``autonomy: {yes: low}`` fires at High and
    Full); otherwise the outcome is *requested* and waits until the operator approves it, forces another one
    (operator tool: ``approve PATH`` / ``force PATH OUTCOME``) or raises the autonomy. Without a suggestion
    the state waits until the operator forces an outcome. The hint is logged for the operator on entry.

    -- outcomes    list  The choices (at least one), e.g. [yes, no].
    -- hint        str   What to decide, shown to the operator ("" for none).
    -- suggestion  str   The outcome proposed by the robot, one of outcomes ("" for none: the operator decides).

    <= {outcomes}  The outcome chosen (the suggestion once allowed, or the operator's).
    """

    def __init__(self, outcomes: Sequence[str] = ("yes", "no"), hint: str = "", suggestion: str = "") -> None:
        owner = type(self).__name__
        choices = validation.names(owner, "outcomes", outcomes, allow_empty=False)
        super().__init__(outcomes=choices)
        self._hint = validation.text(owner, "hint", hint)
        suggestion = validation.text(owner, "suggestion", suggestion)
        if suggestion and suggestion not in choices:
            raise ConfigError(choices_message(f"{owner}: suggestion", suggestion, choices))
        self._suggestion = suggestion

    @property
    def suggestion(self) -> str:
        return self._suggestion

    def on_enter(self, userdata: UserDataView) -> None:
        offer = ", ".join(self.outcomes)
        suggested = f"; suggested: {self._suggestion}" if self._suggestion else "; no suggestion: choose one"
        text = f"{self._hint} " if self._hint else ""
        self.log_hint(f"{text}[{offer}]{suggested}")

    def execute(self, userdata: UserDataView) -> Optional[str]:
        return self._suggestion or None
