"""OccupancyMap: insertion, batched queries, voxel extraction, ray casting, files, bad arrays."""

import numpy as np
import pytest

import sonarmap


def test_wall_is_occupied_and_the_way_to_it_free(small_map):
    labels = small_map.classify(np.array([[2.05, 0.0, 0.0], [1.0, 0.0, 0.0], [-3.0, 0.0, 0.0]]))
    assert labels.dtype == np.int8 and labels.shape == (3,)
    assert list(labels) == [1, 0, -1]
    p = small_map.occupancy(np.array([[2.05, 0.0, 0.0], [1.0, 0.0, 0.0], [-3.0, 0.0, 0.0]]))
    assert p.dtype == np.float64
    assert p[0] == pytest.approx(0.7, abs=1e-6) and p[1] == pytest.approx(0.4, abs=1e-6) and np.isnan(p[2])


def test_batched_queries_equal_single_queries(small_map):
    rng = np.random.default_rng(7)
    points = rng.uniform(-0.5, 2.5, size=(500, 3))
    points[:, 1:] *= 0.4
    labels = small_map.classify(points)
    occupancy = small_map.occupancy(points)
    log_odds = small_map.log_odds(points)
    assert set(np.unique(labels)) <= {-1, 0, 1} and len(np.unique(labels)) == 3
    for i in range(0, len(points), 7):
        assert small_map.classify(points[i])[0] == labels[i]
        assert small_map.classify(points[i : i + 1])[0] == labels[i]
        single = small_map.occupancy(points[i])[0]
        assert (np.isnan(single) and np.isnan(occupancy[i])) or single == occupancy[i]
        assert np.isnan(log_odds[i]) == (labels[i] == -1)


def test_strided_arrays_are_read_in_place(small_map):
    points = np.zeros((40, 6))
    points[:, 0] = np.linspace(0.0, 2.2, 40)
    strided = points[:, ::2]  # (40, 3) with a stride of 16 bytes between columns
    assert not strided.flags.c_contiguous
    assert np.array_equal(small_map.classify(strided), small_map.classify(np.ascontiguousarray(strided)))
    fortran = np.asfortranarray(points[:, :3])
    assert np.array_equal(small_map.classify(fortran), small_map.classify(points[:, :3].copy()))


@pytest.mark.parametrize(
    "bad, message",
    [
        (np.zeros((4, 2)), "shape"),
        (np.zeros((4, 3, 1)), "shape"),
        (np.zeros(4), "shape"),
        (np.zeros((4, 3), dtype=np.float32), "float64"),
        (np.zeros((4, 3), dtype=np.int8), "float64"),
        (np.array([[0.0, 0.0, np.nan]]), "finite"),
        (np.array([[0.0, np.inf, 0.0]]), "finite"),
        ("not an array", "float64"),
    ],
)
def test_bad_points_raise_value_error(small_map, bad, message):
    with pytest.raises(sonarmap.ValueError, match=message):
        small_map.classify(bad)
    with pytest.raises(sonarmap.ValueError, match=message):
        small_map.occupancy(bad)
    with pytest.raises(sonarmap.ValueError, match=message):
        small_map.insert_point_cloud(bad, np.zeros(3))


def test_bad_origin_raises_value_error(small_map):
    with pytest.raises(sonarmap.ValueError, match="origin"):
        small_map.insert_point_cloud(np.ones((2, 3)), np.zeros(2))
    with pytest.raises(sonarmap.ValueError, match="origin"):
        small_map.insert_point_cloud(np.ones((2, 3)), np.array([np.nan, 0.0, 0.0]))
    with pytest.raises(sonarmap.ValueError, match="direction"):
        small_map.cast_ray(np.zeros(3), np.zeros(3))


def test_insert_stats_and_max_range():
    m = sonarmap.OccupancyMap(0.1)
    stats = m.insert_point_cloud(np.array([[1.0, 0.0, 0.0], [5.0, 0.0, 0.0]]), [0, 0, 0], max_range=2.0)
    assert stats.points == 2 and stats.rays == 2 and stats.occupied_updates == 1
    # keys 32768 .. 32788 along x (the 5 m ray clipped at 2 m): 6 bricks of 4 voxels, 8 B each, in
    # the crossed and the hit sets
    assert stats.key_set_bytes == 2 * 6 * 8
    assert m.classify(np.array([[5.0, 0.0, 0.0], [1.5, 0.0, 0.0]])).tolist() == [-1, 0]


def test_voxels_counts_and_memory(small_map):
    centers, sizes = small_map.occupied_voxels()
    assert centers.shape == (len(sizes), 3) and centers.dtype == np.float64
    assert len(sizes) > 0 and np.allclose(sizes, 0.1)
    assert np.all(small_map.classify(centers) == 1)
    free_centers, free_sizes = small_map.free_voxels()
    assert free_centers.shape[1] == 3 and np.all(free_sizes >= 0.1 - 1e-12)
    assert np.all(small_map.classify(free_centers) == 0)
    all_centers, all_sizes, log_odds = small_map.leaves()
    assert len(all_sizes) == len(sizes) + len(free_sizes) == small_map.num_leaf_nodes()
    assert log_odds.dtype == np.float32
    assert small_map.num_nodes() == small_map.num_leaf_nodes() + small_map.num_inner_nodes()
    assert small_map.memory_bytes() > 0 and small_map.memory_bytes_allocated() >= small_map.memory_bytes()
    assert "OccupancyMap(resolution=0.1 m" in repr(small_map) and small_map.stats is None


def test_cast_ray(small_map):
    hit = small_map.cast_ray([0.0, 0.0, 0.0], [1.0, 0.0, 0.0])
    assert hit is not None and hit.shape == (3,) and hit[0] == pytest.approx(2.05)
    assert small_map.cast_ray([0.0, 0.0, 0.0], [-1.0, 0.0, 0.0]) is None  # unknown space first
    assert small_map.cast_ray([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], max_range=1.0) is None


@pytest.mark.parametrize("extension", [".bt", ".ot"])
def test_write_read_round_trip(small_map, tmp_path, extension):
    path = tmp_path / ("map" + extension)
    small_map.write(str(path))
    again = sonarmap.OccupancyMap.read(str(path))
    assert again.resolution == pytest.approx(0.1)
    centers, _ = small_map.leaves()[:2]
    assert np.array_equal(again.classify(centers), small_map.classify(centers))
    again.write(str(tmp_path / ("again" + extension)))
    assert (tmp_path / ("again" + extension)).read_bytes() == path.read_bytes()


def test_bad_and_truncated_map_files(small_map, tmp_path):
    good = tmp_path / "map.bt"
    small_map.write(str(good))
    data = good.read_bytes()
    truncated = tmp_path / "truncated.bt"
    truncated.write_bytes(data[: len(data) - 10])
    with pytest.raises(sonarmap.FileError, match="truncated.bt"):
        sonarmap.OccupancyMap.read(str(truncated))
    garbage = tmp_path / "garbage.bt"
    garbage.write_bytes(b"# not an octomap file\nhello\n")
    with pytest.raises(sonarmap.FileError):
        sonarmap.OccupancyMap.read(str(garbage))
    wrong = tmp_path / "wrong.ot"
    wrong.write_bytes(data)  # a .bt body under an .ot name
    with pytest.raises(sonarmap.FileError):
        sonarmap.OccupancyMap.read(str(wrong))


def test_copy_is_deep(small_map):
    twin = small_map.copy()
    twin.insert_point_cloud(np.array([[-1.0, 0.0, 0.0]]), np.zeros(3))
    assert small_map.classify(np.array([[-1.0, 0.0, 0.0]]))[0] == -1
    assert twin.classify(np.array([[-1.0, 0.0, 0.0]]))[0] == 1


def test_paths_may_be_pathlib_paths(small_map, tmp_path):
    """Every file argument takes str or os.PathLike (pathlib.Path), as Python's own open() does."""
    path = tmp_path / "map.bt"
    small_map.write(path)
    assert sonarmap.OccupancyMap.read(path).num_leaf_nodes() == small_map.num_leaf_nodes()
    with pytest.raises(sonarmap.FileError):
        sonarmap.read_sonar_log(tmp_path / "missing.mat")
    with pytest.raises(sonarmap.FileError):
        sonarmap.read_nav_csv(tmp_path / "missing.csv")
