"""The live source in Python (docs/live.md, "From Python"): frames sent by `myoshell send` and by
LiveSender arrive value for value and are counted; a port in use is refused with the library's
message; LiveFace drives a Simulator through the C++ mapping (the activations it sets are the
mapped ones) and moves the skin. No test sleeps: waits end on the frame's arrival."""
import csv
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import myoshell
from conftest import SOURCE_TREE

# Every LiveFace says once, as `myoshell live` does, which inputs drive nothing here (asserted below).
pytestmark = pytest.mark.filterwarnings("ignore:.* drives nothing:UserWarning")

TAKE = SOURCE_TREE / "tests" / "anim" / "performances" / "livelink_take.csv"


def take_weights():
    """The take's rows as dicts ARKit name -> value (Live Link's column names, first letter lowered)."""
    names = set(myoshell.arkit_names())
    rows = []
    with open(TAKE) as f:
        for row in csv.DictReader(f):
            rows.append({k[0].lower() + k[1:]: float(v) for k, v in row.items() if k[0].lower() + k[1:] in names})
    return rows


def cli_program():
    program = os.environ.get("MYOSHELL_BIN") or str(SOURCE_TREE / "build" / "bin" / "myoshell")
    if not os.access(program, os.X_OK):
        pytest.skip(f"no myoshell program at {program} (build it, or set MYOSHELL_BIN)")
    return program


def test_frames_sent_by_the_cli_arrive_value_for_value():
    program = cli_program()
    expected = take_weights()
    assert len(expected) == 3 and len(expected[0]) == 52
    with myoshell.LiveSource("livelink", port=0, lockstep=True) as source:
        assert source.port > 0 and source.input == "livelink"
        sender = subprocess.Popen([program, "send", str(TAKE), "--to", "livelink", f"127.0.0.1:{source.port}",
                                   "--lockstep"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        received = []
        try:
            while len(received) < len(expected) and source.wait_for_frame(10.0):
                received.append(source.take_newest())  # taking it acknowledges: the sender sends the next
        finally:
            out, err = sender.communicate(timeout=20)
        assert sender.returncode == 0, err
        counters = source.counters()
    assert len(received) == 3
    for k, (sample, row) in enumerate(zip(received, expected)):
        assert sample.sequence == k + 1
        weights = sample.weights
        assert list(weights) == myoshell.arkit_names()
        for name, value in row.items():
            assert weights[name] == np.float32(value), (k, name)  # the packet carries float32
        np.testing.assert_array_equal(sample.weight_array, [weights[n] for n in myoshell.arkit_names()])
        assert sample.head_pose is not None and len(sample.head_pose) == 3  # Live Link carries the head
    assert counters["packets"] == 3 and counters["frames"] == 3 and counters["taken"] == 3
    assert counters["superseded"] == 0 and counters["malformed"] == 0 and counters["dropped"] == 0


@pytest.mark.parametrize("protocol", ["livelink", "vmc"])
def test_a_slow_consumer_gets_only_the_newest_frame(protocol):
    with myoshell.LiveSource(protocol, port=0) as source:
        sender = myoshell.LiveSender(protocol, port=source.port)
        for k in range(3):
            sender.send({"jawOpen": 0.1 * (k + 1), "mouthSmileLeft": 0.25})
        assert source.wait_for_packets(3, 10.0)
        sample = source.take_newest()
        assert source.take_newest() is None  # nothing new since
        counters = source.counters()
    assert sample.sequence == 3
    assert sample.weights["jawOpen"] == np.float32(0.3) and sample.weights["mouthSmileLeft"] == 0.25
    assert sum(sample.weight_array != 0) == 2
    assert counters["frames"] == 3 and counters["superseded"] == 2 and counters["taken"] == 1


def test_a_port_in_use_is_refused_with_the_librarys_message():
    with myoshell.LiveSource("vmc", port=0) as first:
        port = first.port
        with pytest.raises(myoshell.InputError, match=f"port {port} on 127.0.0.1 is in use \\(another receiver"):
            myoshell.LiveSource("vmc", port=port)
    with myoshell.LiveSource("vmc", port=port) as again:  # closing freed it
        assert again.port == port
    with pytest.raises(myoshell.InputError, match="unknown live input 'osc' \\(use vmc or livelink\\)"):
        myoshell.LiveSource("osc", port=0)
    with pytest.raises(myoshell.InputError, match="port: expected a whole number in 1–65535, got 70000"):
        myoshell.LiveSender("vmc", port=70000)
    with pytest.raises(myoshell.InputError, match="'chin' is not one of ARKit's 52"):
        myoshell.LiveSample({"chin": 0.5})


def test_live_face_sets_the_mapped_activations_and_moves_the_skin(face):
    sim = myoshell.Simulator(face)
    live = myoshell.LiveFace(sim, filter=False)
    with pytest.warns(UserWarning, match="tongueOut drives nothing"):
        applied = live.apply({"mouthSmileLeft": 0.8, "mouthSmileRight": 0.8, "jawOpen": 0.4}, now=0.0)
    assert applied["liveness"] == 1.0 and not applied["calibrating"]
    acts = applied["activations"]
    assert set(acts) <= set(face.muscle_names) and max(acts.values()) > 0.1
    # The simulator holds exactly what the C++ mapping gave (LiveFaceMapper::apply), muscle by muscle.
    held = sim.activations()
    for name, value in acts.items():
        assert held[name] == value, name
    sim.step(20)
    assert np.abs(sim.displacement()).max() > 0.01  # cm: the smile moved the skin

    # The same weights as a LiveSample received: the same mapping, the same activations.
    other = myoshell.Simulator(face)
    myoshell.LiveFace(other, filter=False).apply(
        myoshell.LiveSample({"mouthSmileLeft": 0.8, "mouthSmileRight": 0.8, "jawOpen": 0.4}), now=0.0)
    assert other.activations() == held


def test_live_face_maps_as_a_recorded_take_plays(face, cache_dir, tmp_path):
    """One mapping path: each frame of the take applied live sets the activations the scene player's
    timeline sets at that frame when the same take is played as a recording (filter off in both)."""
    scene = tmp_path / "take.json"
    scene.write_text(json.dumps({"name": "take", "model": "anatomical", "muscles": {"library": "face"},
                                 "performance": {"file": str(TAKE), "filter": {"enabled": False}}}))
    player = myoshell.ScenePlayer(scene, cache=str(cache_dir))
    sim = myoshell.Simulator(face)
    live = myoshell.LiveFace(sim, filter=False)
    rows = take_weights()
    assert player.frame_count == len(rows)
    shared = set(player.muscle_names) & set(face.muscle_names)
    assert len(shared) >= 8
    driven = 0
    for k, row in enumerate(rows):
        t = player.frame_time(k)
        player.restart(t)
        player.play_to(t + player.dt)  # one step, its timeline applied at t
        recorded = player.activations()
        applied = live.apply(row, now=t)["activations"]
        for name in shared:
            assert applied[name] == pytest.approx(recorded[name], rel=1e-9, abs=1e-12), (k, name)
        driven = max(driven, sum(applied[name] > 0.01 for name in shared))
    assert driven >= 4  # the take's smile and jaw drive several muscles


def test_live_face_holds_then_eases_to_neutral(face):
    sim = myoshell.Simulator(face)
    live = myoshell.LiveFace(sim, filter=False, timeout=0.5, ease=0.5)
    with myoshell.LiveSource("livelink", port=0) as source:
        myoshell.LiveSender("livelink", port=source.port).send({"mouthSmileLeft": 0.9, "mouthSmileRight": 0.9})
        assert source.wait_for_frame(10.0)
        arrival_guess = myoshell.live_clock()
        first = live.update(source, now=arrival_guess)
    sample = first["sample"]
    assert sample is not None and sample.arrival <= arrival_guess
    assert max(first["activations"].values()) > 0.1
    held = live.apply(None, now=sample.arrival + 0.4)  # within the timeout: the frame is held
    assert held["liveness"] == 1.0 and held["activations"] == first["activations"]
    easing = live.apply(None, now=sample.arrival + 0.75)  # halfway through the ease: smoothstep 0.5
    assert easing["liveness"] == pytest.approx(0.5)
    gone = live.apply(None, now=sample.arrival + 1.5)
    assert gone["liveness"] == 0.0 and max(gone["activations"].values()) == 0.0
    assert max(sim.activations().values()) == 0.0


def test_live_face_refuses_what_it_cannot_drive(face):
    with pytest.raises(myoshell.InputError, match="give a Simulator or a ScenePlayer"):
        myoshell.LiveFace(face)
    with pytest.raises(myoshell.InputError, match="timeout, the ease and the calibration"):
        myoshell.LiveFace(myoshell.Simulator(face), timeout=-1.0)
