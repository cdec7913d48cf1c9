"""PriorityContainer: a state machine that pauses every state outside it while it is active.

Typical use: one branch of a concurrency container watches a hazard; when it fires, the branch
enters a priority container (stop, back up, clear the costmap) and the other branches (e.g. path
following) are paused (``on_pause``) until the priority container finishes, then resume
(``on_resume``) and continue. States inside the container run normally. Priority containers nest:
the innermost active one wins. The claim is held by the behavior's context, never by the class.
"""

from __future__ import annotations

from flex_nav.behavior.state_machine import StateMachine


class PriorityContainer(StateMachine):
    """A StateMachine that, while active, holds all states outside it (FlexBE's PriorityContainer)."""

    kind = "priority container"

    def _activate(self, now: float) -> None:
        super()._activate(now)
        rt = self.__flex_nav_runtime__
        assert rt.ctx is not None
        rt.ctx.claim_priority(rt)

    def _leave(self) -> None:
        super()._leave()
        self._release()

    def _abort(self) -> None:
        super()._abort()
        self._release()

    def _release(self) -> None:
        rt = self.__flex_nav_runtime__
        ctx = rt.ctx
        if ctx is not None and rt in ctx.priority:
            ctx.release_priority(rt, ctx.now())
