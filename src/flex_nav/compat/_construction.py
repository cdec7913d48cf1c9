"""The "opened container" of SMACH's and FlexBE's construction idiom, without global state.

Both libraries build containers like this::

    with sm:
        StateMachine.add("FOO", Foo(), transitions={"done": "BAR"})   # a call on the class

The class-level ``add`` acts on the container opened by the innermost ``with``. SMACH and FlexBE keep
that in a class attribute (one stack per process, guarded by a lock); here the stack is a
``contextvars`` variable, so each thread (and each asyncio task) has its own and two behaviors can be
built at the same time. :class:`construction_method` is the descriptor that makes ``Class.add(...)``
and ``instance.add(...)`` both work: on the class it needs an opened container; on an instance it uses
the opened container when there is one (as SMACH does) and the instance itself otherwise.
"""

from __future__ import annotations

import contextvars
import functools
from typing import Any, Callable, Generic, Optional, Tuple, TypeVar

T = TypeVar("T")


class OpenedStack(Generic[T]):
    """A per-context stack of containers opened for construction (innermost last)."""

    def __init__(self, name: str) -> None:
        self._var: contextvars.ContextVar[Tuple[T, ...]] = contextvars.ContextVar(name, default=())

    def push(self, container: T) -> None:
        self._var.set((*self._var.get(), container))

    def pop(self, container: T) -> bool:
        """Remove ``container`` if it is the innermost one; False if it is not (nothing is changed then)."""
        stack = self._var.get()
        if not stack or stack[-1] is not container:
            return False
        self._var.set(stack[:-1])
        return True

    def top(self) -> Optional[T]:
        stack = self._var.get()
        return stack[-1] if stack else None

    def contains(self, container: T) -> bool:
        return any(c is container for c in self._var.get())


class construction_method:  # noqa: N801  (used like @staticmethod)
    """``Class.method(...)`` acts on the opened container; ``instance.method(...)`` too, or on the instance.

    ``resolve(owner_class)`` returns the opened container the class-level call must act on (and raises
    the library's error when there is none, or it has the wrong type).
    """

    def __init__(self, func: Callable[..., Any], resolve: Callable[[type], Any], is_open: Callable[[], bool]) -> None:
        self._func = func
        self._resolve = resolve
        self._is_open = is_open
        functools.update_wrapper(self, func)  # type: ignore[arg-type]

    def __get__(self, obj: Any, owner: type) -> Callable[..., Any]:
        func = self._func
        resolve = self._resolve
        is_open = self._is_open

        @functools.wraps(func)
        def bound(*args: Any, **kwargs: Any) -> Any:
            target = resolve(owner) if obj is None or is_open() else obj
            return func(target, *args, **kwargs)

        return bound
