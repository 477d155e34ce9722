"""`python -m bench.ai`'s paired comparison (a saved run replays seed for seed, and the
report counts the seeds only one version won) and its refit of the pot-chance model."""

from __future__ import annotations

import argparse
import json
import re
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from bench.ai import (
    Arm,
    Counts,
    _map,
    balls_to_pot,
    end_of_rack,
    log_loss,
    main,
    model_rates,
    noise_parts,
    rank_correlation,
    refit,
    report_chances,
    report_counts,
    runout_position,
    sign_test,
)
from bench.breaks import break_once, strokes
from bench.breaks import main as breaks_main
from server.ai import Bot, Turn, play_turn
from server.ai.aiming import aimed, strike_gain
from server.ai.bot import BREAKS, BreakStroke
from server.ai.geometry import ChanceModel
from server.ai.search import TIPS
from server.engine import BALL_RADIUS, Shot
from server.rules import ANYWHERE, Foul, Game, Outcome


def test_the_sign_test_is_the_two_sided_binomial_tail() -> None:
    assert sign_test(0, 0) == 1.0
    assert sign_test(4, 4) == 1.0
    assert sign_test(8, 0) == pytest.approx(2 / 256)
    assert sign_test(0, 8) == pytest.approx(2 / 256)
    # 25 against 12 discordant seeds: p = 2 * P(X <= 12), X ~ Binomial(37, 1/2).
    assert sign_test(25, 12) == pytest.approx(0.04703, abs=1e-5)


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_a_saved_run_replays_seed_for_seed_and_the_report_counts_differences(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    first, second = tmp_path / "first.json", tmp_path / "second.json"
    args = ["--runouts", "2", "--seed", "3", "--only", "runouts"]
    main([*args, "--save", str(first)])
    saved = json.loads(first.read_text())
    assert sorted(saved["runouts"]) == ["3", "4"]
    # Pretend the earlier version lost seed 3 whatever it did: a rack won only now when
    # this run clears it, a difference of nothing otherwise.
    flipped = {"runouts": {**saved["runouts"], "3": not saved["runouts"]["3"]}}
    first.write_text(json.dumps(flipped))
    capsys.readouterr()
    main([*args, "--save", str(second), "--paired", str(first)])
    assert json.loads(second.read_text()) == saved  # the same seeds, the same outcomes
    report = capsys.readouterr().out
    now_only, then_only = (1, 0) if saved["runouts"]["3"] else (0, 1)
    assert f"won only now {now_only}, only then {then_only};" in report
    assert "of 2;" in report
    # Every rack not cleared is put down to how it ended.
    ends = re.search(r"racks not cleared: (.*)", report)
    assert ends is not None, report
    counted = [int(part.split()[0]) for part in ends[1].split(", ") if part != "none"]
    assert sum(counted) == 2 - sum(saved["runouts"].values())
    # And to the balls it had left to pot.
    left = re.search(r"racks not cleared, by the balls left to pot \(the 8 counted\): (.*)", report)
    assert left is not None, report
    by_left = [part.split(" with ") for part in left[1].split(", ") if part != "none"]
    assert sum(int(n) for n, _ in by_left) == sum(counted)
    assert all(1 <= int(k) <= 15 for _, k in by_left)
    assert "pots made by the chance planned" in report


def test_the_ladder_plays_only_the_steps_asked_for(tmp_path: Path) -> None:
    """`--steps`: a change to one level is measured on its step alone; the others, whose
    play it does not touch, are not replayed."""
    saved = tmp_path / "ladder.json"
    main(["--only", "ladder", "--steps", "amateur", "--games", "2", "--save", str(saved)])
    outcomes = json.loads(saved.read_text())
    assert list(outcomes) == ["eight_ball amateur vs beginner"]
    assert sorted(outcomes["eight_ball amateur vs beginner"]) == ["0", "1"]
    with pytest.raises(SystemExit):
        main(["--only", "ladder", "--steps", "beginner"])  # the weakest level has no step


def test_the_carom_benchmark_finds_the_engine_corrected_aims_drop_more(
    capsys: pytest.CaptureFixture[str],
) -> None:
    from bench.caroms import main as caroms

    caroms(["--tables", "80", "--seed", "0"])
    report = capsys.readouterr().out
    match = re.search(r"geometry's aim (\d+)%, corrected (\d+)%", report)
    assert match is not None, report
    raw, corrected = int(match.group(1)), int(match.group(2))
    assert corrected > raw + 20  # the secant of engine shots finds the aims that drop
    strokes = re.search(r"(\d+) strokes", report)
    assert strokes is not None and int(strokes[1]) > 30


def test_the_carom_benchmark_measures_billiards_and_their_corrected_aims_drop_more(
    capsys: pytest.CaptureFixture[str],
) -> None:
    from bench.caroms import main as caroms

    caroms(["--tables", "150", "--seed", "0", "--kind", "billiard"])
    report = capsys.readouterr().out
    assert report.startswith("billiards on 150 random tables"), report
    match = re.search(r"geometry's aim (\d+)%, corrected (\d+)%", report)
    assert match is not None, report
    raw, corrected = int(match.group(1)), int(match.group(2))
    assert corrected > raw + 20  # the cue ball's bend after the glance, found by the engine
    strokes = re.search(r"(\d+) strokes", report)
    assert strokes is not None and int(strokes[1]) > 30


def _kernels_compiled(_: int) -> bool:
    from server.ai import geometry

    return bool(geometry._pot_kernel.signatures) and bool(geometry._open_kernel.signatures)


def test_each_worker_loads_the_compiled_kernels_before_its_first_job() -> None:
    """A worker's first plan would otherwise count numba's compiling in the plan time."""
    assert _map(_kernels_compiled, [0, 1], jobs=2) == [True, True]


def _outcome(pocketed: tuple[int, ...] = (), foul: bool = False, over: bool = False) -> Outcome:
    fouls = (Foul("scratch", "the cue ball went in"),) if foul else ()
    keeps = bool(pocketed) and not foul and not over
    return Outcome(1, pocketed, fouls, keeps, 1 if keeps else 0, None, over, None, None, "")


def test_a_lost_rack_is_put_down_to_how_it_ended() -> None:
    sure, hard = Turn(kind="pot", chance=0.95), Turn(kind="pot", chance=0.6)
    assert end_of_rack(sure, _outcome(), lost=False) == "missed a sure pot"
    assert end_of_rack(hard, _outcome(), lost=False) == "missed a harder pot"
    assert end_of_rack(Turn(kind="safety"), _outcome(), lost=False) == "played safe"
    assert end_of_rack(Turn(kind="kick"), _outcome((3,)), lost=False) == "played safe"
    assert end_of_rack(sure, _outcome((3,), foul=True), lost=False) == "fouled"
    assert end_of_rack(sure, _outcome((8,), over=True), lost=True) == "lost on the 8"


def test_pots_are_counted_by_the_chance_their_plan_gave_them(
    capsys: pytest.CaptureFixture[str],
) -> None:
    counts, more = Counts(), Counts()
    dropped, missed = _outcome((3,)), _outcome()
    for chance, outcome in ((1.0, dropped), (1.0, dropped), (0.95, missed), (0.93, dropped)):
        counts.tally("pro", Turn(kind="pot", chance=chance), outcome)
    counts.tally("pro", Turn(kind="pot", chance=0.3), missed)
    more.tally("pro", Turn(kind="pot", chance=1.0), missed)
    more.tally("pro", Turn(kind="safety"), missed)
    counts.add(more)
    assert (counts.pot_tries["pro"], counts.pots["pro"], counts.safeties["pro"]) == (6, 3, 1)
    report_chances(counts, "pro")
    line = capsys.readouterr().out
    assert "0-50 %: 0/1; 90-100 %: 1/2; 100 %: 2/3" in line


def test_the_chance_refit_finds_the_model_the_rates_came_from() -> None:
    # Pots whose rates are exactly what a model of the grid says: the refit must give it
    # back, and it must order them as well as a model can.
    rng = np.random.default_rng(3)
    n = 400
    data = np.column_stack(
        [
            rng.uniform(0.1, 2.0, n),  # cue -> object, m
            rng.uniform(0.1, 2.0, n),  # object -> pocket, m
            rng.uniform(0.0, 1.2, n),  # cut, rad
            (rng.uniform(size=n) < 0.3).astype(float),  # side pocket
            rng.uniform(0.5, 1.0, n),  # cos of the approach
            np.zeros(n),
        ]
    )
    aim = Bot(Bot.LEVELS[-1]).level.aim
    truth = ChanceModel(aim_scale=1.6, floor=0.01, cut=0.02, jaw=0.024, side=0.01)
    data[:, 5] = model_rates(data, truth, aim, BALL_RADIUS)
    loss, found = refit(data, aim, BALL_RADIUS)
    assert found == truth
    assert loss == log_loss(data[:, 5], data[:, 5])
    assert rank_correlation(data[:, 5], data[:, 5]) == pytest.approx(1.0)
    assert rank_correlation(-data[:, 5], data[:, 5]) < -0.999  # ties at the clip aside


def test_bench_breaks_ranks_the_strokes_and_marks_the_computers_break(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert breaks_main(["--kind", "nine_ball", "--racks", "3", "--top", "2"]) == 0
    out = capsys.readouterr().out
    assert f"nine_ball, {len(strokes())} strokes x 3 racks (seeds 1000-1002)" in out
    rows = [line for line in out.splitlines() if re.match(r"\s*\d+\s+\d\.\d\d", line)]
    assert 2 <= len(rows) <= 3  # the best two, and the computer's own when it is not
    marked = [row for row in rows if row.endswith("<- the computer's break")]
    own = BREAKS["nine_ball"]
    assert len(marked) == 1 and f"{own.offset:5.2f} {own.speed:5.1f}" in marked[0]
    for row in rows:  # the last column: how open the breaks left the rack, 0 to 1
        spread = float(re.findall(r"%\s+(\d\.\d{3})", row)[-1])
        assert 0.0 <= spread <= 1.0


def test_a_break_too_soft_to_open_the_rack_keeps_nothing() -> None:
    soft = break_once("eight_ball", 1000, BreakStroke(0.0, 1.0), "pro")
    assert (soft.breaks, soft.kept, soft.kept_with_pot, soft.won) == (1, 0, 0, 0)
    tuned = [break_once("eight_ball", s, BREAKS["eight_ball"], "pro") for s in range(1000, 1010)]
    assert sum(t.kept for t in tuned) >= 6
    assert all(t.kept_with_pot <= t.kept for t in tuned)
    # A soft break leaves the rack packed: few of its balls have a clear pot.
    assert soft.open_sum < 0.3 < sum(t.open_sum for t in tuned) / len(tuned)


def test_the_counts_say_how_often_a_player_kept_the_table_after_breaking(
    capsys: pytest.CaptureFixture[str],
) -> None:
    counts = Counts(games=2)
    for speed in (BREAKS["eight_ball"].speed, 1.0):  # the tuned break, and one too soft
        game = Game.new("eight_ball", ["pro", "other"], seed=1001)
        bot = Bot("pro", seed=1)
        turn = bot.plan(game, 0)
        assert turn.kind == "break" and turn.shot is not None
        turn = replace(turn, shot=replace(turn.shot, speed=speed))
        outcome, _ = play_turn(game, 0, turn)
        assert outcome is not None
        counts.tally("pro", turn, outcome)
    assert (counts.breaks["pro"], counts.breaks_kept["pro"]) == (2, 1)
    report_counts(counts, ["pro"])
    assert "kept the table after 1/2 breaks" in capsys.readouterr().out


def test_the_runouts_noise_parts_play_the_same_draws_with_parts_left_out() -> None:
    """`--noise`: every variant draws the same four normals a stroke, so a seed's racks
    differ only by the parts left out; the full error is the bot's own."""
    bot = Bot("pro")
    shot = aimed(0.3, 2.0, 0.2, 0.1)

    def play(parts: tuple[str, ...]) -> Shot:
        return Arm(bot.level, parts).execute(shot, np.random.default_rng(5))

    full = play(("aim", "speed", "tip"))
    assert full == bot.execute(shot, np.random.default_rng(5))
    assert play(()) == shot
    aim = play(("aim",))
    assert (aim.speed, aim.tip) == (shot.speed, shot.tip)
    # The tip's error changes the spin, not the line: the line is the aim's alone.
    assert full.tip != shot.tip
    assert full.direction() == pytest.approx(aim.direction(), abs=1e-12)
    # With "squirt" the tip's error turns the line too, by the squirt of the tip struck.
    squirted = play(("aim", "speed", "tip", "squirt"))
    assert squirted.tip == full.tip
    turned = squirted.direction() - aim.direction()
    assert turned == pytest.approx(full.squirt() - shot.squirt(), abs=1e-12)
    assert abs(turned) > 1e-5
    # The speed's sigma is the cue's (FastFiz's); with "ball-speed" it is the ball's own.
    rng = np.random.default_rng(5)
    draw = [float(rng.normal(0.0, 1.0)) for _ in range(4)][1]
    assert full.speed - shot.speed == pytest.approx(draw * 0.075 * strike_gain(0.2, 0.1))
    ball = play(("aim", "speed", "tip", "ball-speed"))
    assert ball.speed - shot.speed == pytest.approx(draw * 0.075)
    assert (ball.angle, ball.tip) == (full.angle, full.tip)
    assert noise_parts("aim,speed,tip,squirt") == ("aim", "speed", "tip", "squirt")
    assert noise_parts("none") == ()
    with pytest.raises(argparse.ArgumentTypeError, match="unknown noise part 'wind'"):
        noise_parts("aim,wind")


def test_the_runouts_start_on_the_table_asked_for_with_ball_in_hand_on_an_open_table() -> None:
    """`--table`: the rack is broken and run on that table (the tournaments' FastFiz table,
    2.236 x 1.116 m, is nearest the 8ft), every ball inside its outline (a ball may rest in
    a pocket's jaws, past the bed)."""
    for size, length, width in (("8ft", 2.34, 1.17), ("9ft", 2.54, 1.27)):
        game = runout_position(3, np.random.default_rng(3 + 999), size)
        table = game.table
        assert (table.length, table.width) == (length, width)
        assert (game.turn, game.ball_in_hand, game.groups, game.over) == (1, ANYWHERE, None, False)
        on_table = game.balls.on_table_ids()
        assert 8 in on_table and len(on_table) >= 10
        for ball in on_table:
            x, y = game.balls.positions[game.balls.index(ball)]
            assert 0.0 < x < length and 0.0 < y < width, (size, ball, x, y)
        # On the open table every object ball is still to pot; once the groups are
        # chosen, the seat's group and the 8.
        assert balls_to_pot(game, 1) == len(on_table) - 1
        game.groups = ("solids", "stripes")
        solids = [b for b in on_table if 1 <= b <= 7]
        assert balls_to_pot(game, 0) == len(solids) + 1


def test_the_nine_ball_runouts_start_with_ball_in_hand_and_the_nine_on_the_table(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """`--kind nine_ball`: the same start on a 9-ball rack (no push out after the break),
    every object ball to pot, and the run saved under its own key."""
    game = runout_position(3, np.random.default_rng(3 + 999), "9ft", "nine_ball")
    assert game.kind == "nine_ball"
    assert (game.turn, game.ball_in_hand, game.push_out_available) == (1, ANYWHERE, False)
    on_table = game.balls.on_table_ids()
    assert 9 in on_table and set(on_table) <= set(range(10))
    assert balls_to_pot(game, 1) == len(on_table) - 1
    saved = tmp_path / "nine.json"
    main(
        [
            "--runouts",
            "1",
            "--seed",
            "3",
            "--only",
            "runouts",
            "--kind",
            "nine_ball",
            "--save",
            str(saved),
        ]
    )
    assert list(json.loads(saved.read_text())) == ["nine_ball runouts"]
    report = capsys.readouterr().out
    assert "9-ball rack, no push out" in report
    cleared = json.loads(saved.read_text())["nine_ball runouts"]["3"]
    assert cleared or "(the 9 counted)" in report


def test_the_stroke_benchmark_finds_a_soft_draw_arrives_too_slow(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """Struck at the same speed, a draw slides all the way to its ball and a follow
    hardly slides: the soft draws drop far less often than the soft follows."""
    from bench.strokes import FACTORS, main, pot_rates

    rates = pot_rates(30, 5)
    assert set(rates) == {(f, tip) for f in FACTORS for tip in TIPS}
    assert all(0.0 <= rate <= 1.0 for rate in rates.values())
    slowest = FACTORS[0]
    assert rates[slowest, (0.0, -0.35)] + 0.3 < rates[slowest, (0.0, 0.35)], rates
    main(["--pots", "3", "--seed", "1"])
    report = capsys.readouterr().out
    assert "3 random pots" in report and report.count("%") >= len(FACTORS) * len(TIPS)


def test_the_leaves_fit_finds_the_weights_the_outcomes_came_from() -> None:
    from bench.leaves import logistic_fit

    rng = np.random.default_rng(4)
    x = rng.uniform(0.0, 1.0, (20000, 2))
    truth = np.array([-1.5, 3.0, 1.0])
    p = 1.0 / (1.0 + np.exp(-(truth[0] + x @ truth[1:])))
    y = (rng.uniform(size=len(p)) < p).astype(float)
    assert np.allclose(logistic_fit(x, y), truth, atol=0.15)


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_the_leaves_benchmark_counts_each_table_the_runout_kept(
    capsys: pytest.CaptureFixture[str],
) -> None:
    """Each kept table of a runout is described as the search sees it and carries the
    rack's outcome; the report's table counts every one of them."""
    from bench.ai import runout
    from bench.leaves import kept_tables
    from bench.leaves import main as leaves_main

    kept = kept_tables(3)
    cleared, _ = runout(3)
    assert kept, "the runout of rack 3 keeps the table at least once"
    assert all(k.seed == 3 and k.cleared == cleared for k in kept)
    assert all(1 <= k.left <= 15 and 0.0 <= k.q <= 1.0 and 0.0 <= k.open <= 1.0 for k in kept)
    lefts = [k.left for k in kept]
    assert lefts == sorted(lefts, reverse=True) and len(set(lefts)) == len(lefts)  # a ball a pot
    leaves_main(["--racks", "1", "--seed", "3"])
    report = capsys.readouterr().out
    assert f"kept tables: {len(kept)};" in report
    cells = re.findall(r"(\d+): +\d+ %", report)
    assert sum(int(c) for c in cells) == len(kept)
    assert "the search's quality" in report
