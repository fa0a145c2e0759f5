"""GeoJSON coordinates that are not JSON numbers (strings, booleans) are refused, naming
the point or polygon: numpy's and shapely's conversions would read them silently."""

import json

import numpy as np
import pytest

from voroforge.io.readers import read_points
from voroforge.io.readers.geojson import read_geojson_polygons


def _write(tmp_path, geoms):
    feats = [{"type": "Feature", "geometry": g, "properties": {}} for g in geoms]
    p = tmp_path / "in.geojson"
    p.write_text(json.dumps({"type": "FeatureCollection", "features": feats}))
    return p


@pytest.mark.parametrize("bad", ["0.5", True, None, [0.5]])
def test_point_coordinates_must_be_numbers(tmp_path, bad):
    pts = [
        {"type": "Point", "coordinates": [0.1, 0.2]},
        {"type": "Point", "coordinates": [bad, 0.3]},
    ]
    with pytest.raises(ValueError, match=r"point 1's coordinates are not \[x, y\] numbers"):
        read_points(_write(tmp_path, pts))


def test_numbers_and_multipoints_are_read(tmp_path):
    pts = [
        {"type": "Point", "coordinates": [1, 2.5]},
        {"type": "MultiPoint", "coordinates": [[3, 4], [5e-300, -6]]},
    ]
    np.testing.assert_array_equal(
        read_points(_write(tmp_path, pts)), [[1, 2.5], [3, 4], [5e-300, -6]]
    )


@pytest.mark.parametrize("bad", ["1", False])
def test_polygon_coordinates_must_be_numbers(tmp_path, bad):
    ring = [[0, 0], [1, 0], [1, bad], [0, 1], [0, 0]]
    with pytest.raises(ValueError, match="polygon 0's coordinates are not numbers"):
        read_geojson_polygons(_write(tmp_path, [{"type": "Polygon", "coordinates": [ring]}]))
    ring[2] = [1, 1]
    assert (
        read_geojson_polygons(_write(tmp_path, [{"type": "Polygon", "coordinates": [ring]}])).area
        == 1.0
    )
