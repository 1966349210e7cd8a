# step() releases the GIL: two simulations step from two Python threads at once, each ending in
# the state it reaches alone, and other Python threads run while a step is in progress.
import threading
import time

import tacta

from conftest import beam_scene


def final_hash(ticks):
    sim = tacta.Simulation.from_dict(beam_scene())
    sim.step(ticks)
    return sim.report()["state_hash"]


def test_two_simulations_on_two_threads():
    alone = final_hash(1500)
    results = [None, None]
    sims = [tacta.Simulation.from_dict(beam_scene()) for _ in results]

    def work(i):
        for _ in range(15):
            sims[i].step(100)
        results[i] = sims[i].report()["state_hash"]

    threads = [threading.Thread(target=work, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results == [alone, alone]


def test_python_runs_while_a_step_runs():
    sim = tacta.Simulation(str(__import__("conftest").ROOT / "scenes/liver_palpation.yaml"))
    span = {}

    def work():
        span["start"] = time.monotonic()
        sim.step(1500)  # one call: with the GIL held for it, nothing below could run meanwhile
        span["end"] = time.monotonic()

    stamps = []
    worker = threading.Thread(target=work)
    worker.start()
    while worker.is_alive():
        stamps.append(time.monotonic())
    worker.join()
    during = [t for t in stamps if span["start"] < t < span["end"]]
    assert len(during) > 100
