"""NEAT ask/tell, HyperNEAT decoding, runs written as the CLI writes them, replays."""

from __future__ import annotations

import csv
import json
import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

import vivae

XOR = [((0.0, 0.0), 0.0), ((0.0, 1.0), 1.0), ((1.0, 0.0), 1.0), ((1.0, 1.0), 0.0)]


def xor_fitness(genome: vivae.Genome) -> float:
    net = genome.network()
    error = sum(abs(net.activate([a, b, 1.0])[0] - want) for (a, b), want in XOR)
    return (4.0 - error) ** 2


def evolve_xor(seed: int, generations: int = 300):
    pop = vivae.Population(3, 1, seed=seed)
    for _ in range(generations):
        fitnesses = [xor_fitness(g) for g in pop.ask()]
        pop.tell(fitnesses)
        if max(fitnesses) >= 15.0:
            break
    return pop


def test_xor_is_solved_by_ask_tell_with_a_python_fitness():
    pop = evolve_xor(seed=1)
    genome, fitness, _ = pop.best_ever
    assert fitness >= 15.0
    net = genome.network()
    for (a, b), want in XOR:
        assert abs(net.activate([a, b, 1.0])[0] - want) < 0.5


def test_ask_tell_runs_repeat_bit_for_bit_and_restore_from_json():
    a, b = evolve_xor(seed=4, generations=20), evolve_xor(seed=4, generations=20)
    assert a.to_json() == b.to_json()
    restored = vivae.Population.from_json(a.to_json())
    for pop in (a, restored):
        pop.tell([xor_fitness(g) for g in pop.ask()])
    assert restored.to_json() == a.to_json()


def test_tell_with_the_wrong_count_is_a_value_error():
    pop = vivae.Population(3, 1, size=20)
    assert len(pop.ask()) == 20
    with pytest.raises(ValueError, match="19"):
        pop.tell([0.0] * 19)
    with pytest.raises(ValueError):
        pop.tell([0.0] * 20, behaviours=[[1.0]] * 3)
    pop.tell([1.0] * 20, behaviours=[[1.0, 2.0]] * 20)
    assert pop.stats()["best_fitness"] == 1.0


def test_network_refuses_the_wrong_number_of_inputs():
    genome = vivae.Population(3, 1, size=5).ask()[0]
    with pytest.raises(ValueError, match="inputs"):
        genome.network().activate([1.0])


def test_unknown_neat_params_are_value_errors():
    with pytest.raises(ValueError, match="nonsense"):
        vivae.Population(3, 1, params={"nonsense": 1})


def test_genome_json_round_trips_and_a_malformed_one_is_a_value_error():
    genome = vivae.Population(3, 1, size=5).ask()[0]
    again = vivae.Genome.from_json(genome.to_json())
    assert again.to_json() == genome.to_json()
    with pytest.raises(ValueError):
        vivae.Genome.from_json('{"nodes": 3}')


def test_hyperneat_decode_gives_numpy_weights_on_the_substrate():
    task = vivae.DriveTask(sensors="3x5", neurons="3x3", steps=50)
    pop = task.population(size=10)
    assert task.cppn_shape == (5, 3)
    genome = pop.ask()[0]
    d = task.decode(genome)
    assert d["input_weights"].shape == (9, 15)
    assert d["recurrent_weights"].shape == (9, 9)
    assert d["biases"].shape == (9,)
    assert d["input_weights"].dtype == np.float64
    left, right = d["wheels"]
    assert 0 <= left < 9 and 0 <= right < 9 and left != right


def test_drive_task_evaluates_genomes_as_a_run_does():
    task = vivae.DriveTask(steps=60, population=12)
    pop = task.population()
    genomes = pop.ask()
    fitness = task.evaluate(genomes)
    assert len(fitness) == 12 and all(f >= 0 for f in fitness)
    assert fitness == task.evaluate(genomes)
    assert task.episode(genomes[0])["fitness"] == fitness[0]
    pop.tell(fitness)
    assert pop.best_ever[1] == max(fitness)


def test_the_controller_drives_the_environment():
    import gymnasium

    task = vivae.DriveTask(robots=1, steps=30)
    genome = task.population(size=5).ask()[0]
    controller = task.controller(genome)
    env = gymnasium.make("vivae/Drive-v0", steps=30)
    obs, _ = env.reset(seed=0)
    for _ in range(30):
        wheels = controller.act(obs[None, :].astype(np.float64))
        assert wheels.shape == (1, 2)
        obs, *_ = env.step(wheels[0].astype(np.float32))
    with pytest.raises(ValueError, match="shape"):
        controller.act(np.zeros((2, 15)))


SETTINGS = dict(generations=3, population=16, steps=80, seed=5, threads=2)
FLAGS = ["--generations", "3", "--population", "16", "--steps", "80", "--seed", "5", "--threads", "2"]
SAME = [
    "config.toml",
    "scenario.svg",
    "generations.csv",
    "population.csv",
    "best-genomes.jsonl",
    "champion.json",
]


def checkpoint_without_wall_times(path: Path) -> str:
    """A checkpoint's text but its checksum and the length of timing.csv it
    records (wall times differ between any two runs, the CLI's included)."""
    header, payload = path.read_text().split("\n", 1)
    assert header.startswith("vivae-checkpoint ") and payload.count('"timing_len":') == 1
    return re.sub(r'"timing_len":[0-9]+', '"timing_len":_', payload)


def test_evolve_writes_the_same_run_directory_as_the_cli(tmp_path, cli):
    ours = tmp_path / "py"
    result = vivae.evolve(out=ours, progress=False, **SETTINGS)
    theirs = tmp_path / "cli"
    subprocess.run([cli, "evolve", "-q", "--out", str(theirs), *FLAGS], check=True, stdout=subprocess.DEVNULL)
    for name in SAME:
        assert (ours / name).read_bytes() == (theirs / name).read_bytes(), name
    cps = sorted(p.name for p in (theirs / "checkpoints").iterdir())
    assert cps == sorted(p.name for p in (ours / "checkpoints").iterdir())
    for name in cps:
        assert checkpoint_without_wall_times(ours / "checkpoints" / name) == checkpoint_without_wall_times(
            theirs / "checkpoints" / name
        ), name
    assert len((ours / "timing.csv").read_text().splitlines()) == 4
    assert result["generations"] == 3 and result["finished"]
    champion = json.loads((ours / "champion.json").read_text())
    assert result["best"] == champion["fitness"]
    # replay measures what the CLI's replay prints.
    printed = subprocess.run([cli, "replay", str(theirs), "--out", str(tmp_path / "r")], check=True,
                             capture_output=True, text=True).stdout
    fields = dict(kv.split("=") for kv in printed.split())
    measured = vivae.replay(ours)
    assert repr(measured["fitness"]) == fields["fitness"] or measured["fitness"] == float(fields["fitness"])
    assert f"{measured['on_road']:.4f}" == fields["on_road"]
    assert f"{measured['speed']:.4f}" == fields["speed"]
    assert f"{measured['collisions']:.3f}" == fields["collisions"]
    assert str(measured["left_turns"]) == fields["left_turns"]


@pytest.mark.parametrize("strategy, own", [("novelty", None), ("map-elites", "archive.jsonl"), ("nsga2", "front.jsonl"),
                                           ("one-plus-lambda", "parent.json")])
def test_evolve_with_a_strategy_writes_what_the_cli_writes(tmp_path, cli, strategy, own):
    ours = tmp_path / "py"
    vivae.evolve(out=ours, progress=False, strategy=strategy, behaviour="side-speed", **SETTINGS)
    theirs = tmp_path / "cli"
    flags = ["--strategy", strategy, "--behaviour", "side-speed", *FLAGS]
    subprocess.run([cli, "evolve", "-q", "--out", str(theirs), *flags], check=True, stdout=subprocess.DEVNULL)
    for name in SAME + ([own] if own else []):
        assert (ours / name).read_bytes() == (theirs / name).read_bytes(), name
    assert f'kind = "{strategy}"' in (ours / "config.toml").read_text()
    with pytest.raises(ValueError, match="strategy"):
        vivae.evolve(out=tmp_path / "bad", progress=False, strategy="cma-es", **SETTINGS)


@pytest.mark.parametrize("strategy", ["neat", "novelty"])
def test_evolve_runs_the_maze_as_the_cli_does(tmp_path, cli, strategy):
    settings = dict(generations=3, population=20, seed=4, threads=1)
    ours = tmp_path / "py"
    result = vivae.evolve(out=ours, progress=False, task="maze", strategy=strategy, **settings)
    theirs = tmp_path / "cli"
    flags = ["--task", "maze", "--strategy", strategy, "--generations", "3", "--population", "20", "--seed", "4",
             "--threads", "1"]
    printed = subprocess.run([cli, "evolve", "-q", "--out", str(theirs), *flags], check=True,
                             capture_output=True, text=True).stdout
    for name in SAME:
        assert (ours / name).read_bytes() == (theirs / name).read_bytes(), name
    fields = dict(kv.split("=", 1) for kv in printed.split() if "=" in kv)
    assert fields["solved"] == ("yes" if result["solved"] else "no")
    assert fields["evals_to_solve"] == ("none" if result["evals_to_solve"] is None else str(result["evals_to_solve"]))
    assert result["evaluations"] == int(fields["evaluations"])
    # A config file says which task it is; the keyword may not contradict it.
    with pytest.raises(ValueError, match="experiment.task"):
        vivae.evolve(out=tmp_path / "bad", progress=False, config=ours / "config.toml", task="driving")


def test_es_hyperneat_tasks_evaluate_and_replay_as_runs_do(tmp_path):
    task = vivae.DriveTask(steps=60, population=12, substrate="es-hyperneat")
    genomes = task.population().ask()
    fitness = task.evaluate(genomes)
    assert any(f > 0 for f in fitness)
    # Episodes drive the ES network too; the dense sheet's arrays do not exist.
    assert [task.episode(g)["fitness"] for g in genomes] == fitness
    with pytest.raises(ValueError, match="es-hyperneat"):
        task.decode(genomes[0])
    result = vivae.evolve(out=tmp_path / "es", progress=False, substrate="es-hyperneat", **SETTINGS)
    assert vivae.replay(tmp_path / "es")["fitness"] == result["best"]


def test_es_leo_keys_of_a_config_file_seed_the_population_and_the_run(tmp_path):
    config = tmp_path / "leo.toml"
    config.write_text('[substrate]\nkind = "es-hyperneat"\n\n[substrate.es]\nleo = true\nleo_seed = true\n')
    task = vivae.DriveTask(config=config, steps=60, population=12)
    assert "leo = true" in task.config_toml() and "leo_seed = true" in task.config_toml()
    # Generation 0 is LEO's locality seed: one Gaussian hidden node per CPPN.
    genomes = task.population().ask()
    assert [g.num_hidden for g in genomes] == [1] * 12
    assert [g.to_json() for g in task.population().ask()] == [g.to_json() for g in genomes]
    result = vivae.evolve(out=tmp_path / "leo", progress=False, config=config, **SETTINGS)
    assert "leo_seed = true" in (tmp_path / "leo" / "config.toml").read_text()
    assert vivae.replay(tmp_path / "leo")["fitness"] == result["best"]
    # The keys apply to ES only, and the seed feeds LEO's output.
    for text, needle in [
        ("[substrate.es]\nleo = true\n", "substrate.es.leo"),
        ('[substrate]\nkind = "es-hyperneat"\n[substrate.es]\nleo_seed = true\n', "substrate.es.leo_seed"),
    ]:
        bad = tmp_path / "bad.toml"
        bad.write_text(text)
        with pytest.raises(ValueError, match=needle):
            vivae.DriveTask(config=bad)


def test_evolve_reports_each_generation_and_replay_returns_the_measures(tmp_path):
    seen = []
    result = vivae.evolve(out=tmp_path / "run", progress=True, on_generation=seen.append, **SETTINGS)
    assert [r["generation"] for r in seen] == [1, 2, 3]
    assert seen[-1]["best_ever"] == result["best"]
    measures = vivae.replay(tmp_path / "run")
    assert set(measures) >= {"fitness", "on_road", "collisions", "left_turns", "right_turns", "loops", "side"}
    assert measures["fitness"] == result["best"]
    genome, fitness, _ = vivae.load_genome(tmp_path / "run" / "champion.json")
    assert fitness == result["best"]
    assert genome.to_json() == result["champion"].to_json()


def test_evolve_runs_each_repeated_genome_once_and_says_so(tmp_path):
    seen = []
    result = vivae.evolve(out=tmp_path / "run", progress=False, on_generation=seen.append, **SETTINGS)
    # The first generation has no elites to copy; each later one has some.
    assert seen[0]["reused"] == 0
    assert all(r["reused"] >= 1 for r in seen[1:])
    assert result["evaluations_reused"] == sum(r["reused"] for r in seen)
    placed = vivae.evolve(
        out=tmp_path / "placed", progress=False, scenario="obstacles-random", on_generation=seen.append, **SETTINGS
    )
    assert placed["evaluations_reused"] == 0


def test_evolve_refuses_an_existing_run_and_bad_settings(tmp_path):
    vivae.evolve(out=tmp_path / "run", progress=False, **SETTINGS)
    with pytest.raises(ValueError, match="run"):
        vivae.evolve(out=tmp_path / "run", progress=False, **SETTINGS)
    with pytest.raises(ValueError, match="generations"):
        vivae.evolve(out=tmp_path / "other", progress=False, generations=0)


def test_a_callback_error_stops_the_run_with_a_checkpoint(tmp_path):
    def fail(record):
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        vivae.evolve(out=tmp_path / "run", progress=False, on_generation=fail, **SETTINGS)
    assert (tmp_path / "run" / "checkpoints").is_dir()
    assert len((tmp_path / "run" / "population.csv").read_text().splitlines()) == 1 + 16


def test_replay_of_a_missing_source_is_an_os_error(tmp_path):
    with pytest.raises(OSError, match="nothing.json"):
        vivae.replay(tmp_path / "nothing.json")


def test_an_interrupt_stops_the_run_after_the_generation_with_a_checkpoint(tmp_path):
    def interrupt(record):
        if record["generation"] == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt, match=r"vivae\.resume\("):
        vivae.evolve(out=tmp_path / "run", progress=False, on_generation=interrupt, **SETTINGS)
    checkpoints = sorted(p.name for p in (tmp_path / "run" / "checkpoints").iterdir())
    assert checkpoints[-1] == "gen-000002.ckpt"


def test_a_genome_evolved_by_ask_tell_saves_as_a_champion_the_cli_replays(tmp_path, cli):
    task = vivae.DriveTask(scenario="oval", steps=120, population=12)
    pop = task.population()
    genomes = pop.ask()
    pop.tell(task.evaluate(genomes))
    genome, fitness, _ = pop.best_ever
    path = tmp_path / "elsewhere" / "champion.json"
    path.parent.mkdir()
    task.save_champion(genome, path, fitness)
    assert vivae.replay(path)["fitness"] == fitness == task.episode(genome)["fitness"]
    printed = subprocess.run([cli, "replay", str(path), "--out", str(tmp_path / "r")], check=True,
                             capture_output=True, text=True, cwd=tmp_path).stdout
    assert float(dict(kv.split("=") for kv in printed.split())["fitness"]) == fitness


def test_replay_on_a_placement_of_random_obstacles_and_traffic(tmp_path):
    out = tmp_path / "oncoming"
    vivae.evolve(out=out, progress=False, scenario="oncoming", **SETTINGS)
    default, seven = vivae.replay(out), vivae.replay(out, placement_seed=7)
    assert default == vivae.replay(out, placement_seed=0)
    assert seven == vivae.replay(out, placement_seed=7)
    assert seven != default
    kinds = {"contacts_robot", "contacts_traffic", "contacts_obstacle", "contacts_wall"}
    assert kinds <= set(seven)
    robot, traffic, obstacle = (seven[k] for k in ("contacts_robot", "contacts_traffic", "contacts_obstacle"))
    assert seven["collisions"] == pytest.approx(robot + traffic + obstacle)


def test_replay_with_the_rays_blinded_as_the_cli_does(tmp_path, cli):
    out = tmp_path / "rays"
    vivae.evolve(out=out, progress=False, scenario="corridor", distance_rays=5, **SETTINGS)
    seeing, blind = vivae.replay(out, placement_seed=3), vivae.replay(out, placement_seed=3, blind_rays=True)
    assert blind == vivae.replay(out, placement_seed=3, blind_rays=True)
    assert blind != seeing
    printed = subprocess.run([cli, "replay", str(out), "--placement-seed", "3", "--blind-rays",
                              "--out", str(tmp_path / "r")], check=True, capture_output=True, text=True).stdout
    assert float(dict(kv.split("=") for kv in printed.split())["fitness"]) == blind["fitness"]
    surface = tmp_path / "surface"
    vivae.evolve(out=surface, progress=False, scenario="corridor", **SETTINGS)
    with pytest.raises(ValueError, match="blind_rays=True: the robots carry no distance rays"):
        vivae.replay(surface, blind_rays=True)


def test_replay_lists_the_meetings_with_the_placed_blocks_as_the_cli_does(tmp_path, cli):
    out = tmp_path / "rays"
    vivae.evolve(out=out, progress=False, scenario="corridor", distance_rays=5, **SETTINGS)
    for blind in (False, True):
        r = vivae.replay(out, placement_seed=3, blind_rays=blind, meetings=True)
        args = [cli, "replay", str(out), "--placement-seed", "3", "--meetings", "--out", str(tmp_path / "r")]
        printed = subprocess.run(args + (["--blind-rays"] if blind else []), check=True, capture_output=True,
                                 text=True).stdout.splitlines()
        assert float(dict(kv.split("=") for kv in printed[0].split())["fitness"]) == r["fitness"]
        name = "meetings-p3-blind-rays.csv" if blind else "meetings-p3.csv"
        with open(tmp_path / "r" / name) as f:
            rows = list(csv.DictReader(f))
        # The same meetings, each column as the CSV has it.
        assert len(rows) == len(r["meetings"]) == int(dict(kv.split("=") for kv in printed[-1].split())["meetings"])
        for row, m in zip(rows, r["meetings"]):
            assert int(row["robot"]) == m["robot"] and int(row["block"]) == m["block"]
            assert int(row["touches"]) == m["touches"] and row["exit"] == m["exit"]
            assert abs(float(row["shift"]) - m["shift"]) <= 0.005
            assert (row["seen_at"] == "") == (m["seen_at"] is None)
    assert "meetings" not in vivae.replay(out, placement_seed=3)
    with pytest.raises(ValueError, match="meetings= takes True or False"):
        vivae.replay(out, meetings="yes")
    with pytest.raises(ValueError, match="meetings=True: .*route"):
        vivae.replay(out, scenario="roads", meetings=True)


def test_a_maze_run_takes_its_robot_model_and_other_tasks_refuse_one(tmp_path):
    vivae.evolve(out=tmp_path / "m", task="maze", robot="vivae", generations=1, population=20,
                 threads=1, progress=False)
    assert 'robot = "vivae"' in (tmp_path / "m" / "config.toml").read_text()
    with pytest.raises(ValueError, match="khepera"):
        vivae.evolve(out=tmp_path / "k", task="maze", robot="khepera", generations=1, progress=False)
    with pytest.raises(ValueError, match="one robot model"):
        vivae.evolve(out=tmp_path / "d", robot="vivae", generations=1, progress=False)


def test_maze_networks_start_from_lehmans_hidden_node_unless_the_config_says_otherwise(tmp_path):
    settings = dict(generations=1, population=20, seed=1, threads=1, progress=False)
    lehman = vivae.evolve(out=tmp_path / "lehman", task="maze", **settings)
    assert lehman["champion"].num_hidden == 1
    # NEAT's minimal start and Lehman's novelty distance, from a config file as on the command line.
    config = tmp_path / "direct.toml"
    config.write_text('[experiment]\ntask = "maze"\n[neat]\nstart_hidden = 0\n'
                      '[strategy]\nkind = "novelty"\n[strategy.novelty]\nmetric = "mean-absolute"\n')
    direct = vivae.evolve(out=tmp_path / "direct", config=config, **settings)
    assert direct["champion"].num_hidden == 0
    written = (tmp_path / "direct" / "config.toml").read_text()
    assert 'metric = "mean-absolute"' in written and "start_hidden" not in written
    with pytest.raises(ValueError, match="start_hidden"):
        config.write_text('[experiment]\ntask = "maze"\n[neat]\nstart_hidden = 5000\n')
        vivae.evolve(out=tmp_path / "bad", config=config, **settings)
