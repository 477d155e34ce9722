"""Helpers shared by the server, recovery and browser tests.

- `games`: the fixed rack seeds the tests play and what each of those games does.
- `settings`: fast settings, and settings with a test's own web directory and database.
- `messages`: reading a room's socket (greet, receive until, roundtrip, ...) on anything
  with `send_json`/`receive_json`: a TestClient socket, or `JsonSocket` on a real server.
- `rooms`: apps dealing fixed racks; creating, joining and seating rooms over HTTP (a
  TestClient or an `httpx.Client` on a real server); playing the next shot.
- `live`: a real uvicorn on a port, and the asyncio `websockets` readers for it.
"""
