"""Moved to :mod:`spsc.fem.solid.mesh`: this path re-exports it for code outside ``spsc.fem``
until that code imports the new path."""

from .solid.mesh import (CACHE_DIR, MESH_VERSION, TetMesh, block, boundary_facets, cached_mesh,
                         check_mesh_size, orient_tets, sphere_shell, spsc_wall, wall_mesh_counts,
                         wall_section)

__all__ = ["CACHE_DIR", "MESH_VERSION", "TetMesh", "block", "boundary_facets", "cached_mesh",
           "check_mesh_size", "orient_tets", "sphere_shell", "spsc_wall", "wall_mesh_counts",
           "wall_section"]
