"""Settings from the environment: `POOL_*` overrides, typed like the defaults."""

from __future__ import annotations

from server.config import Settings


def test_overrides_are_typed_like_the_defaults():
    settings = Settings.from_env({"POOL_GRACE": "5", "POOL_SEND_QUEUE": "10",
                                  "POOL_ALLOWED_ORIGINS": "https://a.example, https://b.example",
                                  "POOL_WS_DEFLATE": "1", "UNRELATED": "x"})
    assert settings.grace == 5.0 and settings.send_queue == 10
    assert settings.allowed_origins == ("https://a.example", "https://b.example")
    assert settings.ws_deflate is True
    assert Settings.from_env({"POOL_WS_DEFLATE": "off"}).ws_deflate is False
    assert Settings.from_env({}) == Settings()
    assert Settings().ws_deflate is False  # the default that meets the lateness goal
