"""The angle convention drawn: side view of the eye's frustum, the light and its image plane.

Run by the ``.. plot::`` directive of getting-started.rst when the site is built.
"""

import matplotlib.pyplot as plt
import numpy as np

theta = np.radians(30.0)  # θ = fov/2 for fov = 60°
gamma = np.radians(60.0)  # γ: view direction to the direction towards the light
n, f, n_prime = 1.6, 9.0, 2.4

fig, ax = plt.subplots(figsize=(7.0, 5.0))
t = np.tan(theta)
# view frustum (side view: z along the view direction, y up)
ax.fill([n, f, f, n], [n * t, f * t, -f * t, -n * t], color="#cfe3f6", zorder=0)
ax.plot([0, f], [0, f * t], color="#1f5f99", lw=1.2)
ax.plot([0, f], [0, -f * t], color="#1f5f99", lw=1.2)
ax.plot([n, n], [-n * t, n * t], color="#1f5f99", lw=2)
ax.plot([f, f], [-f * t, f * t], color="#1f5f99", lw=2)
ax.annotate("", xy=(f + 1.0, 0), xytext=(0, 0), arrowprops=dict(arrowstyle="-|>", color="k", lw=1.4))
ax.text(f + 1.05, -0.05, "view\ndirection", va="top", fontsize=10)
ax.plot(0, 0, "ko")
ax.text(0, 0.3, "eye", ha="center", fontsize=10)
ax.text(n, -n * t - 0.25, "near  $n$", ha="center", va="top", fontsize=10)
ax.text(f, -f * t - 0.25, "far  $f$", ha="center", va="top", fontsize=10)
# θ = fov/2
a = np.linspace(0, theta, 30)
ax.plot(1.9 * np.cos(a), 1.9 * np.sin(a), color="#1f5f99")
ax.text(2.0, 0.35, r"$\theta=\mathrm{fov}/2$", fontsize=11, color="#1f5f99")
# direction towards the light, γ from the view direction
d = np.array([np.cos(gamma), np.sin(gamma)])
c = np.array([4.6, 0.0])
ax.annotate("", xy=c + 7.2 * d, xytext=c, arrowprops=dict(arrowstyle="-|>", color="#c8641e", lw=1.8))
ax.text(*(c + 6.6 * d + [-0.3, 0.0]), "towards\nthe light", color="#c8641e", fontsize=10, ha="right")
g = np.linspace(0, gamma, 40)
ax.plot(c[0] + 0.9 * np.cos(g), 0.9 * np.sin(g), color="#c8641e")
ax.text(c[0] + 1.0, 0.55, r"$\gamma$", fontsize=13, color="#c8641e")
# the light's image plane: perpendicular to the light direction, above the frustum
p0 = c + 8.4 * d
u = np.array([d[1], -d[0]])
ax.plot(*np.c_[p0 - 3.3 * u, p0 + 3.3 * u], color="#8a3f9e", lw=2.2)
ax.text(*(p0 - 3.3 * u + [-0.4, 0.1]), "light's image plane\n(the shadow map)", color="#8a3f9e",
        fontsize=10, ha="right", va="bottom")
# warping frustum: centre of projection n' before the near plane
cop = n - n_prime
ax.plot(cop, 0, "s", color="#2e8b57")
ax.annotate("", xy=(n, -1.9), xytext=(cop, -1.9), arrowprops=dict(arrowstyle="<->", color="#2e8b57"))
ax.text((cop + n) / 2, -2.05, r"$n'$", color="#2e8b57", ha="center", va="top", fontsize=12)
ax.text(cop - 0.2, -0.1, "warping frustum's\ncentre of projection\n($n'=n$: PSM, $n'\\to\\infty$: uniform)", color="#2e8b57", ha="right",
        va="center", fontsize=9)
ax.set_aspect("equal")
ax.set_xlim(-5.2, 12.2)
ax.set_ylim(-5.6, 12.6)
ax.axis("off")
ax.set_title(r"fov = 60° ($\theta$ = 30°), $\gamma$ = 60°: $\gamma$ = 90° is overhead, 0° looks into the light, "
             "180° has it behind", fontsize=10)
fig.tight_layout()
