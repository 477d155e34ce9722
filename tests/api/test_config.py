"""Settings from the environment: `POOL_*` overrides, validated, errors naming the variable."""

from __future__ import annotations

from pathlib import Path

import pytest
from pydantic import ValidationError

from server.config import Settings, SettingsError


def test_overrides_are_typed_like_the_defaults():
    settings = Settings.from_env(
        {
            "POOL_GRACE": "5",
            "POOL_SEND_QUEUE": "10",
            "POOL_ALLOWED_ORIGINS": "https://a.example, https://b.example",
            "POOL_WS_DEFLATE": "1",
            "POOL_SOCKET_ORIGINS": "wss://*.pool.example, ws://127.0.0.1:8001",
            "UNRELATED": "x",
        }
    )
    assert settings.grace == 5.0 and settings.send_queue == 10
    assert settings.allowed_origins == ("https://a.example", "https://b.example")
    assert settings.socket_origins == ("wss://*.pool.example", "ws://127.0.0.1:8001")
    assert settings.ws_deflate is True
    assert Settings.from_env({"POOL_WS_DEFLATE": "off"}).ws_deflate is False
    assert Settings.from_env({}) == Settings()
    assert Settings().ws_deflate is False  # the default that meets the lateness goal


def test_the_database_path_is_a_setting_with_its_older_name_kept():
    assert Settings.from_env({}).db_path == Path("billiards.db")
    assert Settings.from_env({"POOL_DB_PATH": "/data/a.db"}).db_path == Path("/data/a.db")
    assert Settings.from_env({"BILLIARDS_DB": "/data/b.db"}).db_path == Path("/data/b.db")
    assert Settings.from_env({"DB_PATH": "/x.db"}).db_path == Path("billiards.db")  # no prefix


@pytest.mark.parametrize(
    ("variable", "value"),
    [
        ("POOL_FRAME_EVERY", "0"),
        ("POOL_GRACE", "abc"),
        ("POOL_SEND_QUEUE", "1e9"),
        ("POOL_PACE", "0"),
        ("POOL_WS_DEFLATE", "maybe"),
        ("POOL_MAX_ROOMS", "0"),
        ("POOL_MAX_SHOT_CLOCK", "601"),
        ("POOL_RATE_PER_SECOND", "nan"),
        ("POOL_SOCKET_ORIGINS", "wss://a.example; script-src *"),  # no more policy through it
        ("POOL_SOCKET_ORIGINS", "https://a.example"),  # sockets only
    ],
)
def test_a_bad_value_is_refused_with_the_variable_named(variable: str, value: str):
    with pytest.raises(SettingsError) as caught:
        Settings.from_env({variable: value})
    assert f"{variable}={value!r}" in str(caught.value)


def test_a_removed_setting_left_in_the_environment_is_ignored(
    monkeypatch: pytest.MonkeyPatch,
):
    """`POOL_FRAMES_PER_MESSAGE` named a setting of the frame stream: a deployment that
    still sets it must start as before."""
    assert Settings.from_env({"POOL_FRAMES_PER_MESSAGE": "4"}) == Settings()
    monkeypatch.setenv("POOL_FRAMES_PER_MESSAGE", "-1")
    started = Settings.from_env()  # no `SettingsError`
    monkeypatch.delenv("POOL_FRAMES_PER_MESSAGE")
    assert started == Settings.from_env()


def test_the_shot_clocks_fit_under_the_maximum():
    assert Settings.from_env({"POOL_MAX_SHOT_CLOCK": "120"}).max_shot_clock == 120.0
    for env in (
        {"POOL_MAX_SHOT_CLOCK": "30"},  # under the default clock, 60
        {"POOL_MAX_SHOT_CLOCK": "4", "POOL_SHOT_CLOCK": "0"},  # under the minimum, 5
    ):
        with pytest.raises(SettingsError, match="POOL_MAX_SHOT_CLOCK"):
            Settings.from_env(env)


def test_settings_built_in_code_ignore_the_environment(monkeypatch: pytest.MonkeyPatch):
    monkeypatch.setenv("POOL_GRACE", "1")
    assert Settings().grace == 60.0
    assert Settings.from_env().grace == 1.0


def test_replace_validates_and_settings_are_frozen():
    settings = Settings(pace=2.0)
    assert settings.replace(pace=3.0).pace == 3.0 and settings.pace == 2.0
    with pytest.raises(ValidationError):
        settings.replace(frame_every=0)
    with pytest.raises(ValidationError):
        settings.pace = 5.0  # type: ignore[misc]


def test_the_server_command_names_a_bad_variable(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
):
    from server.__main__ import main

    monkeypatch.setenv("POOL_FRAME_EVERY", "0")
    with pytest.raises(SystemExit) as stopped:
        main([])
    assert stopped.value.code == 2
    assert "POOL_FRAME_EVERY='0'" in capsys.readouterr().err
