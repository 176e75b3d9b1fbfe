"""Animations of a trajectory: GIF through pillow, MP4 where ffmpeg is installed."""

from __future__ import annotations

import math
import os
import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_count, check_number, check_size
from kinematica.io.atomic import atomic_path, unchanged
from kinematica.robot import Robot
from kinematica.viz._mpl import (
    VizError,
    check_picture,
    equal_limits,
    figure,
    matplotlib,
    new_axes,
)
from kinematica.viz.arm import ArmDrawing, extent_points
from kinematica.viz.geometry import ArmPose, arm_pose, drawing_plane, robot_scale
from kinematica.viz.plot import label_axes, tight_single
from kinematica.viz.ticks import fit_ticks
from kinematica.viz.trajectory import PATH_COLOR, check_trajectory

__all__ = [
    "ANIMATION_SUFFIXES",
    "GIF_MAX_FPS",
    "MAX_FPS",
    "MAX_RESAMPLED",
    "MIN_FPS",
    "Animation",
    "animate",
    "animation_samples",
    "gif_rate",
    "mp4_available",
]

FloatArray = NDArray[np.float64]

#: File types an animation can be written as.
ANIMATION_SUFFIXES = (".gif", ".mp4")
#: Frames per second when the trajectory has no times.
DEFAULT_FPS = 20.0
#: At most this many frames unless asked otherwise (a GIF of thousands of frames
#: takes minutes to draw and megabytes to store).
MAX_FRAMES = 300
#: Frame rates an animation plays at: a frame every 100 s at the slowest (a GIF
#: holds delays up to 655 s), 240 frames a second at the fastest.
MIN_FPS, MAX_FPS = 0.01, 240.0
#: Most frames a trajectory is resampled into (``fps`` times its duration), before
#: ``max_frames`` keeps some of them.
MAX_RESAMPLED = 1_000_000
#: Fastest frame rate of a GIF. A GIF frame lasts a whole number of hundredths of a
#: second, and browsers play frames shorter than 20 ms at 100 ms: a 100 fps GIF
#: would run ten times too slowly.
GIF_MAX_FPS = 50.0


@dataclass(frozen=True)
class Animation:
    """A written animation.

    Attributes:
        path: The file.
        frames: Number of frames in it.
        fps: Frames per second it plays at.
        size: ``(width, height)`` in pixels.
        note: What was changed from the rate asked for, or ``""``: a GIF plays
            at most :data:`GIF_MAX_FPS`.
    """

    path: Path
    frames: int
    fps: float
    size: tuple[int, int]
    note: str = ""


def mp4_available() -> bool:
    """True when matplotlib finds an ``ffmpeg`` executable to write MP4 files."""
    matplotlib()
    from matplotlib import animation

    return bool(animation.writers.is_available("ffmpeg"))


def gif_rate(rate: float) -> float:
    """The rate a GIF is written at for ``rate`` asked: at most :data:`GIF_MAX_FPS`."""
    return min(rate, GIF_MAX_FPS)


def _resample(t: FloatArray, q: FloatArray, fps: float) -> tuple[FloatArray, FloatArray]:
    """Times every ``1 / fps`` s from ``t[0]`` to ``t[-1]``, and q interpolated at them."""
    count = math.floor(float(t[-1] - t[0]) * fps + 1e-9) + 1
    times = t[0] + np.arange(count) / fps
    return times, np.stack([np.interp(times, t, q[:, j]) for j in range(q.shape[1])], axis=-1)


def animation_samples(
    t: FloatArray,
    q: FloatArray,
    fps: float | None,
    max_frames: int | None,
    timed: bool,
    gif: bool = False,
) -> tuple[FloatArray, FloatArray, float]:
    """The times, configurations and frame rate of the frames to draw.

    Without ``fps`` every sample is one frame, played in real time when
    ``timed`` (frame rate ``(T - 1) / duration``) or at :data:`DEFAULT_FPS`.
    With ``fps`` (and times) the trajectory is resampled at that rate by
    linear interpolation, in real time. Then at most ``max_frames`` evenly
    spread frames are kept (first and last included), the rate scaled so the
    duration stays the same. For a GIF (``gif``) the rate is then capped at
    :data:`GIF_MAX_FPS`, a timed trajectory resampled at it so that it still
    plays in real time.
    """
    duration = float(t[-1] - t[0])
    if fps is not None:
        fps = check_number(fps, "fps", lo=MIN_FPS, hi=MAX_FPS, what="a number of frames a second")
    if max_frames is not None:
        max_frames = check_count(max_frames, "max_frames", lo=1)
    if fps is not None and timed and len(t) > 1:
        check_size(duration * fps + 1.0, MAX_RESAMPLED, "fps", f"frames over {duration:g} s")
        times, qs = _resample(t, q, fps)
        rate = fps
    else:
        times, qs = t, q
        rate = fps or ((len(t) - 1) / duration if timed and duration > 0 else DEFAULT_FPS)
    if max_frames is not None and len(times) > max_frames:
        keep = np.unique(np.round(np.linspace(0, len(times) - 1, max_frames)).astype(int))
        rate = rate * (len(keep) - 1) / (len(times) - 1) if len(keep) > 1 else rate
        times, qs = times[keep], qs[keep]
    if rate < MIN_FPS:  # real time by the file's own clock: a frame every 1e6 s overflows a GIF
        raise VizError(
            f"the animation would play at {rate:.3g} frames a second ({len(times)} frames over "
            f"{duration:.3g} s), slower than {MIN_FPS:g}: give more frames (max_frames)"
        )
    if gif and gif_rate(rate) != rate:
        rate = gif_rate(rate)  # fewer frames than before: within max_frames still
        if timed and len(t) > 1 and duration > 0:
            times, qs = _resample(t, q, rate)
    return times, qs, rate


def animation_figure(
    robot: Robot,
    q_path: FloatArray,
    q_frames: FloatArray,
    size: tuple[int, int],
    dpi: float,
    frames: bool,
    labels: bool,
) -> tuple[Any, ArmDrawing, Any]:
    """The Figure an animation is drawn on, at its first frame.

    Args:
        robot: The robot.
        q_path: ``(T, n)`` the trajectory's samples (the faint tool path).
        q_frames: ``(F, n)`` the configurations of the frames (the view holds them all).
        size: ``(width, height)`` in pixels.
        dpi: Dots per inch.
        frames: Draw the DH frames.
        labels: Name the frames.

    Returns:
        The Figure, the arm's :class:`ArmDrawing` (moved by its ``update``) and the
        time stamp's Text (``gid="time"``), in the top-right corner, above the axes
        and their ticks.
    """
    fig = figure(*size, dpi, pyplot_managed=False)
    plane = drawing_plane(robot)
    ax = new_axes(fig, plane is None)
    poses = arm_pose(robot, q_frames)
    path_pts = arm_pose(robot, q_path).tool[:, :3, 3]
    shown = path_pts if plane is None else path_pts[:, list(plane)]
    ax.plot(*shown.T, color=PATH_COLOR, lw=1.2, alpha=0.6, gid="tool-path")
    first = ArmPose(poses.origins[0], poses.frames[0], poses.tool[0], poses.joints[0])
    drawing = ArmDrawing(ax, robot, first, plane=plane, frames=frames, labels=labels)
    equal_limits(ax, extent_points(poses, robot_scale(robot)), plane)
    label_axes(ax, plane)
    ax.set_title(robot.name, fontsize=10)
    fit_ticks(ax, 7.0)
    tight_single(fig, plane is None)
    stamp = fig.text(0.99, 0.99, "", fontsize=9, ha="right", va="top", gid="time")
    return fig, drawing, stamp


def animate(
    robot: Robot,
    q: ArrayLike,
    path: str | os.PathLike[str],
    *,
    t: ArrayLike | None = None,
    fps: float | None = None,
    frames: bool = True,
    labels: bool = False,
    size: tuple[int, int] = (640, 560),
    dpi: float = 100.0,
    max_frames: int | None = MAX_FRAMES,
) -> Animation:
    """Write an animation of the arm following a trajectory.

    Args:
        robot: The robot.
        q: ``(T, n)`` joint values (rad, m), one row per sample.
        path: Output file: ``.gif`` (pillow, always) or ``.mp4`` (needs ffmpeg).
        t: ``(T,)`` times (s), strictly increasing; without them the samples
            play at :data:`DEFAULT_FPS`.
        fps: Resample at this many frames per second of ``t`` (linear
            interpolation); ``None`` draws one frame per sample.
        frames: Draw the DH frames.
        labels: Name the frames.
        size: ``(width, height)`` of the animation in pixels.
        dpi: Dots per inch (text size relative to the picture).
        max_frames: Keep at most this many frames, evenly spread (``None``: all).

    Returns:
        The :class:`Animation` written. The tool path is drawn faintly
        (``gid="tool-path"``) and the time shown in the top-right corner of every frame.

    Raises:
        VizError: Unknown file type, MP4 without ffmpeg, a playing rate below MIN_FPS.
        ArgumentError: ``fps``, ``size``, ``dpi`` or ``max_frames`` outside its range.
        DimensionError: ``q`` or ``t`` of the wrong shape.
    """
    out = Path(path)
    suffix = out.suffix.lower()
    if suffix not in ANIMATION_SUFFIXES:
        raise VizError(
            f"{out}: cannot write an animation of type {suffix or '(none)'!r}; use .gif or .mp4"
        )
    if not out.parent.is_dir():
        raise VizError(f"{out}: the folder {out.parent} does not exist")
    checked, dpi = check_picture(size, dpi)
    size = checked or size
    ta, qa = check_trajectory(robot, t, q)
    timed = t is not None
    times, qs, rate = animation_samples(ta, qa, fps, max_frames, timed, gif=suffix == ".gif")
    note = ""
    if suffix == ".gif":
        natural = animation_samples(ta, qa, fps, max_frames, timed)[2]
        if abs(natural - rate) > 1e-9 * natural:
            note = (
                f"{natural:.4g} fps lowered to {rate:.4g} fps: a GIF frame lasts at least "
                "20 ms (browsers play shorter frames at 100 ms)"
            )
    matplotlib()
    from matplotlib import animation

    rate_arg: dict[str, Any] = {"fps": rate}  # matplotlib's stubs say int; any rate works
    writer: Any
    if suffix == ".mp4":
        if not mp4_available():
            raise VizError(f"{out}: writing MP4 needs ffmpeg, which is not installed; write a .gif")
        writer = animation.FFMpegWriter(
            codec="libx264", extra_args=["-pix_fmt", "yuv420p"], **rate_arg
        )
        size = (size[0] + size[0] % 2, size[1] + size[1] % 2)  # yuv420p needs even sizes
    else:
        writer = animation.PillowWriter(**rate_arg)
    fig, drawing, stamp_text = animation_figure(robot, qa, qs, size, dpi, frames, labels)
    poses = arm_pose(robot, qs)

    def at(k: int) -> ArmPose:
        return ArmPose(poses.origins[k], poses.frames[k], poses.tool[k], poses.joints[k])

    decimals = max(2, math.ceil(math.log10(max(rate, 1.0))) + 1)
    try:
        with atomic_path(out) as tmp, writer.saving(fig, str(tmp), dpi):
            for k in range(len(times)):
                drawing.update(at(k))
                stamp = f"t = {times[k]:.{decimals}f} s" if t is not None else f"sample {k + 1}"
                stamp_text.set_text(stamp)
                writer.grab_frame()
    except (OSError, subprocess.CalledProcessError) as exc:
        reason = getattr(exc, "strerror", None) or exc
        raise VizError(f"{out}: cannot write the animation ({reason}); {unchanged(out)}") from exc
    return Animation(path=out, frames=len(times), fps=float(rate), size=size, note=note)
