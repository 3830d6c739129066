# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

"""Type stubs of the `strata` extension module (python/src/*.cpp)."""

from os import PathLike
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

Vec3 = Sequence[float]
Path = Union[str, PathLike[str]]
Progress = Optional[Callable[[float], Optional[bool]]]
Quality = Optional[dict[str, Union[str, float, int, bool]]]

class BadInputError(ValueError):
    """The input is wrong; `file`, `line`, `key`, `value` say where (None where unknown)."""
    file: Optional[str]
    line: Optional[int]
    key: Optional[str]
    value: Optional[str]
    kind: str

class FileError(OSError):
    """A read or write failed; `filename` names the file."""
    kind: str

class GLError(RuntimeError):
    """The GL driver failed (no EGL context, a shader that does not compile)."""
    file: Optional[str]
    line: Optional[int]
    key: Optional[str]
    value: Optional[str]
    kind: str

class MaterialSettings:
    name: str
    side: str
    top: str
    detail: str
    emission: str
    texture_size: int
    texture_seed: int
    mask_maps: bool
    normal_maps: bool
    pbr: Optional[str]
    files: dict[str, str]
    map_scale: float
    blend_offset: float
    blend_exponent: float
    projections: int
    height_strength: float
    albedo_tint: tuple[float, float, float]
    metallic: float
    smoothness: float
    occlusion_strength: float
    normal_strength: float
    normal_blend: str
    detail_scale: float
    layer_blend_depth: float
    layers: list[dict[str, Any]]
    def maps(self) -> dict[str, npt.NDArray[np.uint8]]: ...

class Field:
    lipschitz: float
    def evaluate(self, points: npt.ArrayLike, threads: int = 0) -> npt.NDArray[np.float64]: ...
    def evaluate_lattice(self, origin: Vec3, spacing: Union[float, Vec3], shape: tuple[int, int, int],
                         threads: int = 0) -> npt.NDArray[np.float64]: ...
    def density(self, point: Vec3) -> float: ...
    def bounds(self, min: Vec3, max: Vec3) -> tuple[float, float]: ...

class Scene:
    source: str
    text: str
    seed: int
    voxel_size: float
    half_width: int
    adaptivity: float
    region: tuple[tuple[float, float, float], tuple[float, float, float]]
    input_files: list[str]
    georeference: Optional[tuple[float, float, float]]
    camera: dict[str, Any]
    snapshot: dict[str, Any]
    lighting: dict[str, Any]
    quality: dict[str, Any]
    material: MaterialSettings
    field: Field
    has_landform: bool
    has_rock: bool
    landform_passes: list[dict[str, Any]]
    def field_for_seed(self, seed: int) -> Field: ...
    def resolve_quality(self, preset: Optional[str] = None, quality: Quality = None) -> dict[str, Any]: ...

def default_scene() -> Scene: ...
def default_scene_text() -> str: ...
def load_scene(path: Path, max_memory: int = 0, progress: Progress = None) -> Scene: ...
def parse_scene(text: str, source: str = "<string>", max_memory: int = 0, progress: Progress = None) -> Scene: ...
def set_cache_memory_limit(bytes: int) -> None: ...
def cache_memory_limit() -> int: ...
def cache_memory_used() -> int: ...

class Grid:
    active_voxel_count: int
    voxel_size: float
    memory_bytes: int
    background: float
    seed: Optional[int]
    scene: Optional[Scene]
    field: Optional[Field]
    index_bounds: tuple[tuple[int, int, int], tuple[int, int, int]]
    stats: dict[str, int]
    def dense(self, min: Optional[Sequence[int]] = None, max: Optional[Sequence[int]] = None) -> npt.NDArray[np.float32]: ...
    def save(self, path: Path) -> None: ...

def sample(scene: Scene, seed: Optional[int] = None, preset: Optional[str] = None, quality: Quality = None,
           voxel_size: Optional[float] = None, max_memory: int = 8 << 30, progress: Progress = None) -> Grid: ...
def read_grid(path: Path) -> Grid: ...

class Mesh:
    def __init__(self, vertices: npt.ArrayLike, triangles: npt.ArrayLike, normals: Optional[npt.ArrayLike] = None,
                 origin: Optional[Vec3] = None) -> None: ...
    vertices: npt.NDArray[np.float32]
    normals: Optional[npt.NDArray[np.float32]]
    triangles: npt.NDArray[np.uint32]
    surface: Optional[npt.NDArray[np.float32]]
    landform: Optional[npt.NDArray[np.float32]]
    rock: Optional[npt.NDArray[np.float32]]
    origin: tuple[float, float, float]
    vertex_count: int
    triangle_count: int
    def save(self, path: Path) -> None: ...

def mesh(grid: Grid, preset: Optional[str] = None, mesher: Optional[str] = None, adaptivity: Optional[float] = None,
         normals: Optional[str] = None, projection: Optional[int] = None, simplify: Optional[float] = None,
         quality: Quality = None) -> Mesh: ...
def read_mesh(path: Path) -> Mesh: ...

def render(scene: Scene, mesh: Mesh, backend: str = "cpu", size: Optional[tuple[int, int]] = None, view: str = "",
           debug_view: str = "", camera_position: Optional[Vec3] = None, camera_target: Optional[Vec3] = None,
           fov: Optional[float] = None, preset: Optional[str] = None, quality: Quality = None,
           grid: Optional[Grid] = None) -> npt.NDArray[np.uint8]: ...
def read_image(path: Path) -> npt.NDArray[np.uint8]: ...
def write_image(pixels: npt.ArrayLike, path: Path) -> None: ...

ChunkKey = tuple[int, int, int, int]

class EditShape:
    @staticmethod
    def sphere(centre: Vec3, radius: float) -> EditShape: ...
    @staticmethod
    def box(centre: Vec3, half_size: Vec3, rounding: float = 0.0) -> EditShape: ...
    @staticmethod
    def capsule(a: Vec3, b: Vec3, radius: float) -> EditShape: ...
    @staticmethod
    def path(points: Sequence[Vec3], radius: float) -> EditShape: ...
    def distance(self, point: Vec3) -> float: ...

class World:
    def __init__(self, scene: Scene, voxel_size: Optional[float] = None, chunk_size: int = 32, levels: int = 4,
                 lod_distance: float = 0.0, view_radius: float = 0.0, threads: int = 0,
                 seed: Optional[int] = None, look_ahead: bool = True) -> None: ...
    idle: bool
    stats: dict[str, int]
    def set_points_of_interest(self, points: Sequence[Vec3]) -> None: ...
    def move_to(self, point: Vec3) -> None: ...
    def poll(self, max_updates: int = 0) -> list[tuple[ChunkKey, Optional[Mesh]]]: ...
    def wait_idle(self) -> None: ...
    def dig(self, shape: EditShape, smooth_radius: float = 0.0) -> dict[str, Any]: ...
    def fill(self, shape: EditShape, smooth_radius: float = 0.0) -> dict[str, Any]: ...
    def save_edits(self, path: Path) -> None: ...
    def load_edits(self, path: Path) -> dict[str, Any]: ...
    def density(self, point: Vec3) -> float: ...
    def raycast(self, origin: Vec3, direction: Vec3, max_distance: float) -> Optional[dict[str, Any]]: ...
    def chunk_mesh(self, key: ChunkKey) -> Optional[Mesh]: ...
    def resident_chunks(self) -> list[ChunkKey]: ...
    def chunk_bounds(self, key: ChunkKey) -> tuple[tuple[float, float, float], tuple[float, float, float]]: ...

def bake(scene: Scene, out_dir: Path, tile_size: float = 0.0, lods: int = 3, tiles: str = "all",
         seed: Optional[int] = None, threads: int = 0, grids: bool = True, force: bool = False,
         max_memory: int = 8 << 30, skirt_depth: float = 0.0, progress: Progress = None) -> dict[str, Any]: ...
