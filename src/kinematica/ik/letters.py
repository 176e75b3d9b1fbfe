"""The Robotics Toolbox's configuration letters as a rendering of branch labels.

kinematica names branches in words (``"shoulder right, elbow up, wrist no-flip"``),
read off the arm's geometry as each solver's module says. Peter Corke's Robotics
Toolbox (``ikine_a``, ``ikine_6s``) names the same branches by letters: ``l``/``r``
(left/right arm), ``u``/``d`` (elbow up/down), ``n``/``f`` (wrist no-flip/flip).

Shoulder and elbow agree word for word (208 of 208 comparisons on the Toolbox's
models). The wrist reads the other way: the Toolbox's ``"ruf"`` is the PUMA 560's
nominal pose ``qn = (0, 45°, 180°, 0, 45°, 0)``, which kinematica calls
``"wrist no-flip"`` (104 of 104 comparisons), so ``"wrist no-flip"`` renders as
``f`` and ``"wrist flip"`` as ``n``. Users porting code that filters on the
Toolbox's letters get the Toolbox's meaning.

Parts of a label the Toolbox has no letter for (``"shoulder front"``,
``"root 2"``, ``"link forward"``, the numeric search's label...) render as
nothing: ``"shoulder front, elbow up"`` is ``"u"``.
"""

from __future__ import annotations

__all__ = ["TOOLBOX_LETTERS", "toolbox_letters"]

#: The letter of each part of a label that has one, in the Toolbox's meaning.
TOOLBOX_LETTERS = {
    "shoulder left": "l",
    "shoulder right": "r",
    "elbow up": "u",
    "elbow down": "d",
    "wrist no-flip": "f",  # the reverse of the words: see the module docstring
    "wrist flip": "n",
}


def toolbox_letters(label: str) -> str:
    """The Toolbox's letters of a branch label, shoulder then elbow then wrist.

    Args:
        label: A branch label, e.g. ``"shoulder right, elbow up, wrist no-flip"``.

    Returns:
        e.g. ``"ruf"``; ``""`` when no part of the label has a letter.
    """
    return "".join(TOOLBOX_LETTERS.get(part.strip(), "") for part in label.split(","))
