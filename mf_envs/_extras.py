"""Optional extras: which extra installs a missing module, and how to install it (one line).

Used by the CLI's one-line errors and by the benches that skip rows without an extra.
"""

from __future__ import annotations

# top-level module of an optional dependency -> the extra that installs it (pyproject.toml)
EXTRAS = {
    "stable_baselines3": "train",
    "torch": "train",
    "safetensors": "train",
    "rich": "train",
    "tensorboard": "tensorboard",
    "elastica": "compare",
    "mhkit": "compare",
    "pygame": "render",
    "mpmath": "dev",
    "hypothesis": "dev",
    "ray": "ray",
    "sbx": "sbx",
    "jax": "sbx",
    "capytaine": "hydro",
    "xarray": "hydro",
}


# extras that pull torch: on Linux a plain `pip install torch` is the multi-GB CUDA build
TORCH_EXTRAS = ("train", "ray", "sbx")
CPU_TORCH = "pip install torch==2.13.0 --index-url https://download.pytorch.org/whl/cpu"


def missing_extra(exc: ImportError) -> str | None:
    """The extra whose install fixes `exc` (a ModuleNotFoundError), or None."""
    name = (getattr(exc, "name", None) or "").partition(".")[0]
    return EXTRAS.get(name)


def install_hint(extra: str) -> str:
    """How to install `extra`, on one line (CPU torch first for the extras that need torch)."""
    cmd = f'pip install "mf-envs[{extra}]" (in a clone: pip install -e ".[{extra}]")'
    if extra in TORCH_EXTRAS:
        return f"install CPU torch first: {CPU_TORCH}, then {cmd}"
    return cmd
