"""The transport: HTTP routes, the room WebSocket and the message models."""
