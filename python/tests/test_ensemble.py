"""ddirac.ensemble: members equal their single runs bit for bit, locally and on a Dask cluster (also
when a worker process dies during the run), a failing member is reported while the others finish,
malformed members are refused."""

import os
import signal
import time
from pathlib import Path

import numpy as np
import pytest

import ddirac
from ddirac.ensembles import DIAGNOSTICS

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
DSP = EXAMPLES / "double_spherical_pendulum.toml"
SHORT = {"time.steps": 3000, "time.duration": 30.0, "output.every": 100}


def _members(count):
    return {
        "initial.q.phi1": np.linspace(1.6, 2.4, count),
        "initial.p.vartheta2": np.linspace(0.5, 1.0, count),
    }


def test_members_equal_their_single_runs_bit_for_bit():
    spec = ddirac.load(DSP, overrides=SHORT)
    members = _members(4)
    result = ddirac.ensemble(spec, members=members, trajectories=True, threads=2)
    assert list(result.status) == ["ok"] * 4
    assert result.q.shape == (4, 31, 4)
    for k in range(4):
        overrides = dict(SHORT)
        overrides.update({key: float(values[k]) for key, values in members.items()})
        single = ddirac.load(DSP, overrides=overrides).run()
        assert np.array_equal(result.final_q[k], single.q[-1])
        assert np.array_equal(result.final_p[k], single.p[-1])
        assert np.array_equal(result.q[k], single.q)
        assert np.array_equal(result.energy[k], single.energy)
        assert result.steps[k] == 3000
        e0 = single.energy[0]
        assert result.diagnostics["energy_error"][k] == np.max(np.abs(single.energy - e0))
    assert np.array_equal(result.members["initial.q.phi1"], members["initial.q.phi1"])


def test_a_failing_member_is_reported_and_the_others_finish():
    # With g = 10⁶ the pendulum swings ten radians a step: Newton's method fails, also on sub-steps.
    members = {"initial.p.theta": [0.0, 0.0, 0.0], "initial.p.phi": [0.5, 0.5, 0.8], "parameters.g": [9.8, 1e6, 9.8]}
    spec = ddirac.load(EXAMPLES / "spherical_pendulum.toml", overrides={"time.step": 0.01})
    result = ddirac.ensemble(spec, members=members)
    assert list(result.status) == ["ok", "failed", "ok"]
    (failure,) = result.failures
    assert failure["member"] == 1 and 0 < failure["step"] < 2000
    assert "Newton" in failure["error"]
    assert result.steps[1] == failure["step"]
    assert np.isnan(result.diagnostics["energy_error"][1]) and np.isfinite(result.diagnostics["energy_error"][0])


def test_members_from_a_dataframe_and_from_the_spec_table(tmp_path):
    pandas = pytest.importorskip("pandas")
    frame = pandas.DataFrame(_members(3))
    spec = ddirac.load(DSP, overrides=SHORT)
    from_frame = ddirac.ensemble(spec, members=frame)
    from_dict = ddirac.ensemble(spec, members=_members(3))
    assert np.array_equal(from_frame.final_q, from_dict.final_q)
    table = from_frame.to_pandas()
    assert list(table.columns[:6]) == ["member", "status", "vartheta1", "phi1", "vartheta2", "phi2"]

    text = DSP.read_text() + '\n[ensemble]\nsamples = 2\nseed = 3\n[[ensemble.grid]]\nkey = "initial.q.phi1"\n' \
        'values = [1.8, 2.2]\n[[ensemble.random]]\nkey = "initial.p.vartheta2"\nuniform = [0.5, 1.0]\n'
    path = tmp_path / "generated.toml"
    path.write_text(text)
    generated = ddirac.ensemble(ddirac.load(path, overrides=SHORT))
    assert len(generated) == 4
    assert list(generated.members["initial.q.phi1"]) == [1.8, 1.8, 2.2, 2.2]
    draws = generated.members["initial.p.vartheta2"]
    assert np.all((0.5 <= draws) & (draws < 1.0)) and len(set(draws)) == 4


def test_malformed_members_are_refused_with_the_reason():
    with pytest.raises(ddirac.Error, match="`time.step` cannot vary across members"):
        ddirac.ensemble(DSP, members={"time.step": [0.1]})
    with pytest.raises(ddirac.Error, match="has 1 values, but `initial.q.phi1` has 2"):
        ddirac.ensemble(DSP, members={"initial.q.phi1": [1.0, 2.0], "initial.q.phi2": [1.0]})
    with pytest.raises(ddirac.Error, match="not a finite number"):
        ddirac.ensemble(DSP, members={"initial.q.phi1": [np.nan]})
    with pytest.raises(ddirac.Error, match="no `\\[ensemble\\]` table"):
        ddirac.ensemble(DSP)


@pytest.fixture(scope="module")
def cluster():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            yield client


def test_a_dask_cluster_gives_the_local_result_bit_for_bit(cluster):
    spec = ddirac.load(DSP, overrides=SHORT)
    members = _members(12)
    local = ddirac.ensemble(spec, members=members, trajectories=True)
    remote = ddirac.ensemble(spec, members=members, client=cluster, trajectories=True, chunks=5)
    for name in ("final_q", "final_p", "steps", "q", "p", "energy"):
        assert np.array_equal(getattr(local, name), getattr(remote, name), equal_nan=True), name
    assert list(local.status) == list(remote.status)
    for name in DIAGNOSTICS:
        assert np.array_equal(local.diagnostics[name], remote.diagnostics[name], equal_nan=True), name


def test_a_rigid_body_s_ensemble_on_a_dask_cluster_gives_the_local_result_bit_for_bit(cluster, tmp_path):
    spec = tmp_path / "satellite.toml"
    spec.write_text((EXAMPLES / "satellite_rotors.toml").read_text().replace("duration = 40.0", "duration = 2.0"))
    members = {"initial.v.a2": np.linspace(0.0, 30.0, 6), "initial.Omega.1": np.linspace(0.01, 0.2, 6)}
    local = ddirac.ensemble(spec, members=members, trajectories=True)
    remote = ddirac.ensemble(spec, members=members, client=cluster, trajectories=True, chunks=4)
    assert local.attitude and remote.attitude and local.coordinates == ["a1", "a2", "a3"]
    for name in ("final_R", "final_Pi", "final_q", "final_p", "steps", "R", "Pi", "q", "p", "energy"):
        assert np.array_equal(getattr(local, name), getattr(remote, name), equal_nan=True), name
    assert local.R.shape == (6, 21, 3, 3) and local.q.shape == (6, 21, 3)


def test_a_worker_killed_during_the_run_leaves_the_result_unchanged(cluster):
    # 16 chunks of about 0.1 s each on two one-thread workers; one worker process is killed as soon
    # as it runs a chunk, and Dask runs that chunk again on a live worker.
    import threading

    overrides = {"time.steps": 20000, "time.duration": 200.0, "output.every": 1000}
    spec = ddirac.load(DSP, overrides=overrides)
    members = _members(64)
    local = ddirac.ensemble(spec, members=members)

    pids = cluster.run(os.getpid)
    address, pid = next(iter(pids.items()))
    killed = []

    def kill_when_busy():
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            if cluster.processing().get(address):
                os.kill(pid, signal.SIGKILL)
                killed.append(pid)
                return
            time.sleep(0.005)

    killer = threading.Thread(target=kill_when_busy)
    killer.start()
    remote = ddirac.ensemble(spec, members=members, client=cluster, chunks=16)
    killer.join()
    assert killed, "the worker never ran a chunk"
    assert pid not in cluster.run(os.getpid).values()
    assert np.array_equal(local.final_q, remote.final_q)
    assert np.array_equal(local.final_p, remote.final_p)
    assert list(remote.status) == list(local.status)
    assert np.array_equal(local.steps, remote.steps)
