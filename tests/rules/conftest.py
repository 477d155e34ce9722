import pytest

from server.rules import Game

from .helpers import TABLE


@pytest.fixture
def eight() -> Game:
    return Game.new("eight_ball", ("Ana", "Bob"), table=TABLE)


@pytest.fixture
def nine() -> Game:
    return Game.new("nine_ball", ("Ana", "Bob"), table=TABLE)
