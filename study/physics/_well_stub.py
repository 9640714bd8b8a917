"""PRIVATE STUB of study.physics.well (written by the wellphys branch to the agreed interface): only what the
well branch's code and tests need until that branch is merged; deleted on merge."""

import numpy as np

GRAVITY = 9.80665


def side_load_vector(buoyed_weight, inclination, tension, curvature, direction):
    w = buoyed_weight * np.sin(inclination)
    return w + tension * curvature * np.cos(direction), tension * curvature * np.sin(direction)


def support_moment(w, tension, bending_stiffness, spacing):
    if tension <= 0:
        return -w * spacing**2 / 12.0
    k = np.sqrt(tension / bending_stiffness)
    u = k * spacing / 2.0
    return w / k**2 * (1.0 - u / np.tanh(u))


def midspan_moment(w, tension, bending_stiffness, spacing):
    if tension <= 0:
        return w * spacing**2 / 24.0
    k = np.sqrt(tension / bending_stiffness)
    u = k * spacing / 2.0
    return w / k**2 * (1.0 - u / np.sinh(u))


def beam_column_deflection(x, w, tension, bending_stiffness, spacing):
    x = np.asarray(x, float)
    if tension <= 0:
        return w * x**2 * (spacing - x) ** 2 / (24.0 * bending_stiffness)
    k = np.sqrt(tension / bending_stiffness)
    u = k * spacing / 2.0
    xi = x - spacing / 2.0
    c = w * (spacing / 2.0) / (tension * k * np.sinh(u))
    return c * (np.cosh(k * xi) - np.cosh(u)) + w * ((spacing / 2.0) ** 2 - xi**2) / (2.0 * tension)


def lubinski_bending_stress(youngs_modulus, outer_diameter, curvature, tension, bending_stiffness, half_spacing):
    kl = np.sqrt(tension / bending_stiffness) * half_spacing
    return youngs_modulus * outer_diameter * curvature / 2.0 * (kl / np.tanh(kl) if kl > 0 else 1.0)


def curvature_bending_stress(youngs_modulus, outer_radius, curvature):
    return youngs_modulus * outer_radius * curvature


def rolling_whirl_rate(rotary_speed, radius, clearance):
    return -rotary_speed * radius / clearance
