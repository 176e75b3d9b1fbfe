"""The interactive page inside a notebook cell."""

from __future__ import annotations

import html
from dataclasses import dataclass

from numpy.typing import ArrayLike

from kinematica.robot import Robot
from kinematica.viz._mpl import VizError
from kinematica.viz.page import page_html

__all__ = ["PageView", "page_view"]


@dataclass(frozen=True)
class PageView:
    """The page of :func:`~kinematica.viz.write_page`, shown by Jupyter in an iframe.

    Attributes:
        html: The whole self-contained page.
        height: The iframe's height in CSS pixels.
    """

    html: str
    height: int = 560

    def _repr_html_(self) -> str:
        # srcdoc keeps the page in its own document: its script and styles
        # cannot reach the notebook's, and it needs no file or server.
        return (
            f'<iframe srcdoc="{html.escape(self.html, quote=True)}" '
            f'style="width:100%;height:{self.height}px;border:0" '
            f'sandbox="allow-scripts"></iframe>'
        )


def page_view(
    robot: Robot, q: ArrayLike | None = None, *, euler: str = "ZYZ", height: int = 560
) -> PageView:
    """The interactive page of ``robot`` for a notebook cell (sliders, frames, live T).

    Args:
        robot: The arm.
        q: ``(n,)`` joint values (rad, m) it opens at; zeros if ``None``.
        euler: The Euler sequence the page shows the pose in.
        height: The cell's height in CSS pixels (at least 200).

    Returns:
        An object Jupyter displays as the page (``_repr_html_``).

    Raises:
        VizError: ``height`` is not an integer of at least 200.
    """
    if isinstance(height, bool) or not isinstance(height, int) or height < 200:
        raise VizError(f"height must be an integer of at least 200 (pixels), got {height!r}")
    return PageView(page_html(robot, q=q, euler=euler), height)
