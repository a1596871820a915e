"""Headless rendering for the mf_envs environments (PIL ImageDraw, own perspective projection).

Pure drawing functions return uint8 (H, W, 3) frames and never open a window:
`draw_rigid_body`, `draw_gowec`, `draw_ship`, `draw_inchworm`. `HumanWindow` shows frames for
render_mode="human" (pygame if installed, else matplotlib); `save_gif` writes an animation.
PIL was chosen over matplotlib by measured frame cost (`mf-envs bench speed --scene render`).
"""

from mf_envs.render.gif import save_gif
from mf_envs.render.scene2d import draw_inchworm
from mf_envs.render.scenes3d import draw_gowec, draw_rigid_body, draw_ship
from mf_envs.render.window import HumanWindow

__all__ = [
    "draw_rigid_body",
    "draw_gowec",
    "draw_ship",
    "draw_inchworm",
    "HumanWindow",
    "save_gif",
]
