"""The transport: HTTP routes per resource, the room WebSocket, their bodies, and what
they depend on (`deps`). The services they call live below: `server.ladder`, `server.rooms`,
`server.cluster`, `server.store`."""
