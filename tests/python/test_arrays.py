"""Arrays have the documented shapes and dtypes, and are copies."""
import numpy as np

import myoshell


def test_head_arrays():
    head = myoshell.load_head()
    assert head.name == "default" and head.units == "cm" and head.obj_path is None
    rest, tris = head.rest_positions(), head.triangles()
    assert rest.shape == (head.vertex_count, 3) and rest.dtype == np.float64
    assert tris.shape == (head.triangle_count, 3) and tris.dtype == np.int32
    assert tris.min() >= 0 and tris.max() < head.vertex_count
    assert head.has_jaw
    assert all(0 <= v < head.vertex_count for v in head.landmarks().values())


def test_face_arrays_and_pose_shape(face):
    n = face.vertex_count
    assert face.rest_positions().shape == (n, 3)
    assert face.triangles().dtype == np.int32
    shape = face.pose({"zygomaticus_major_left": 0.5})
    assert shape.shape == (n, 3) and shape.dtype == np.float64 and shape.flags["C_CONTIGUOUS"]
    assert np.abs(shape - face.rest_positions()).max() > 0.05  # cm: the muscle moves the skin
    # Nothing active, upright, gravity on: the rest shape exactly (gravity is relative to the rest).
    assert np.array_equal(face.pose(), face.rest_positions())


def test_returned_arrays_are_copies(face):
    rest = face.rest_positions()
    rest[:] = 0.0
    assert face.rest_positions().any()
    sim = myoshell.Simulator(face)
    p = sim.positions()
    p += 1.0
    assert np.array_equal(sim.positions(), face.rest_positions())


def test_simulator_moves_and_resets(face):
    sim = myoshell.Simulator(face)
    sim.set_activations({"zygomaticus_major_left": 0.8, "zygomaticus_major_right": 0.8})
    sim.step(24)
    assert sim.step_count == 24 and abs(sim.time - 24 * face.dt) < 1e-15
    assert sim.positions().shape == (face.vertex_count, 3)
    assert np.abs(sim.displacement()).max() > 0.01
    assert sim.activations()["zygomaticus_major_left"] == 0.8
    sim.reset()
    assert sim.step_count == 0 and np.array_equal(sim.positions(), face.rest_positions())


def test_muscle_libraries():
    whole = myoshell.muscle_names()  # the default: the whole face
    assert whole == myoshell.muscle_names("face") and len(whole) == 40 and "frontalis_medial_left" in whole
    builtin = myoshell.muscle_names("builtin")
    assert len(builtin) == 10 and "zygomaticus_major_left" in builtin and builtin[-1] == "orbicularis_oris_lower"
    assert set(builtin) <= set(whole)


def test_write_obj_round_trip(face, tmp_path):
    from conftest import read_obj_vertices

    shape = face.pose({"corrugator_supercilii_left": 1.0})
    path = tmp_path / "frown.obj"
    myoshell.write_obj(str(path), face, shape)
    assert np.array_equal(read_obj_vertices(path), shape)


def test_simulators_on_one_face_step_in_threads(face):
    """step() runs without the GIL: two simulators of one face in two threads give the serial results."""
    import threading

    settings = [{"zygomaticus_major_left": 0.9}, {"depressor_anguli_oris_right": 0.5, "corrugator_supercilii_left": 1.0}]

    def run(activations, out, index):
        sim = myoshell.Simulator(face)
        sim.set_activations(activations)
        sim.step(48)
        out[index] = sim.positions()

    serial, parallel = [None, None], [None, None]
    for i, a in enumerate(settings):
        run(a, serial, i)
    threads = [threading.Thread(target=run, args=(a, parallel, i)) for i, a in enumerate(settings)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for i in range(2):
        assert np.array_equal(parallel[i], serial[i])


def test_module_pose_builds_the_same_face(face, cache_dir):
    used = {"depressor_labii_inferioris_left": 0.7}
    assert np.array_equal(myoshell.pose(used, cache=cache_dir, head_pose=(0, 45, 0)),
                          face.pose(used, head_pose=(0, 45, 0)))
    assert myoshell.Face(cache=cache_dir).basis_from_cache

