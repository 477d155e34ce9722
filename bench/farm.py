"""The audit's rating farm, re-played through the real API: a farmer presses Play now, a
fresh profile presses after it, each side strikes (the farmer breaks and scratches, the
fresh profile pots a ball) and the fresh profile concedes; 25 rounds. Prints the farmer's
rating gain (goal: at most 50 points), and what Glicko-2 alone would have given.

    python -m bench.farm [--rounds 25]

Two attacks: every profile from one address (Play now pairs nobody: rounds paired within
`--pair-wait` s), and each fresh profile from an address of its own (127.0.0.x), the
farm the rating rule has to stop.
"""

from __future__ import annotations

import argparse
import asyncio
import tempfile
import time
from pathlib import Path

import httpx

from server.players import KindRating, rate_match
from tests.support.live import live_server, ws_url
from tests.support.settings import settings_in
from tests.support.visits import visit_and_concede

FARMER = "127.0.0.10"
GAME = "eight_ball"


def browser(address: str, source: str) -> httpx.AsyncClient:
    """A browser of its own (a cookie jar) asking from `source`."""
    transport = httpx.AsyncHTTPTransport(local_address=source)
    return httpx.AsyncClient(base_url=f"http://{address}", transport=transport, timeout=60)


async def rating(client: httpx.AsyncClient) -> dict:
    profile = (await client.get("/api/players/me")).json()
    return dict(next(r for r in profile["ratings"] if r["game"] == GAME))


async def one_round(address: str, farmer: httpx.AsyncClient, source: str, wait: float) -> bool:
    """One round against a fresh profile from `source`; False if Play now did not pair
    them within `wait` s (both leave the queue then)."""
    async with browser(address, source) as victim:
        await victim.get("/api/players/me")
        await farmer.post("/api/playnow", json={"game": GAME})
        pressed = (await victim.post("/api/playnow", json={"game": GAME})).json()
        deadline = time.monotonic() + wait
        while pressed["status"] == "waiting" and time.monotonic() < deadline:
            pressed = (await victim.get("/api/playnow", params={"wait": 0.5})).json()
        if pressed["status"] != "matched":
            await victim.delete("/api/playnow")
            await farmer.delete("/api/playnow")
            return False
        seat = (await farmer.get("/api/playnow", params={"wait": 10})).json()["room"]
    room_id = seat["room_id"]
    await visit_and_concede(ws_url(address, room_id), seat["token"], pressed["room"]["token"])
    return True


async def rated(farmer: httpx.AsyncClient, games: int) -> dict:
    """The farmer's rating once `games` results are stored (written behind the game)."""
    deadline = time.monotonic() + 30
    while (now := await rating(farmer))["games"] < games and time.monotonic() < deadline:
        await asyncio.sleep(0.1)
    return now


def glicko_alone(rounds: int) -> float:
    """The farmer's gain by Glicko-2 without the rule: `rounds` wins over new players."""
    farmer = KindRating("farmer", GAME)
    for i in range(rounds):
        farmer, _ = rate_match(farmer, KindRating(f"fresh-{i}", GAME), True, float(i))
    return farmer.rating.rating - 1500.0


async def farm(address: str, rounds: int, one_address: bool, wait: float) -> None:
    async with browser(address, FARMER) as farmer:
        start = await rating(farmer)
        paired = 0
        for i in range(rounds):
            source = FARMER if one_address else f"127.0.0.{20 + i}"
            paired += await one_round(address, farmer, source, wait)
        end = await rated(farmer, paired)
    where = "one address" if one_address else "an address per fresh profile"
    print(
        f"{where}: {paired}/{rounds} rounds paired, farmer {start['rating']:.0f} ->"
        f" {end['rating']:.0f} ({end['rating'] - start['rating']:+.0f} points, goal <= 50;"
        f" {end['games']} games, rd {end['rd']:.0f})"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=25)
    parser.add_argument("--pair-wait", type=float, default=2.0)
    args = parser.parse_args()
    settings = settings_in(Path(tempfile.mkdtemp()), playnow_same_address=False)
    with live_server(settings) as address:
        asyncio.run(farm(address, min(args.rounds, 5), True, args.pair_wait))
        asyncio.run(farm(address, args.rounds, False, args.pair_wait))
    print(f"Glicko-2 without the rule: {glicko_alone(args.rounds):+.0f} points")


if __name__ == "__main__":
    main()
