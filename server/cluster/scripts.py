"""Lua scripts: each runs atomically in Redis, so a check and its write cannot interleave
with another process's."""

from __future__ import annotations

# KEYS: lease, epoch. ARGV: node, ttl ms, floor. The next epoch (above `floor`, the last
# one this caller knows) and the lease, if nobody holds it; else 0.
ACQUIRE = """
if redis.call('EXISTS', KEYS[1]) == 1 then return 0 end
local e = redis.call('INCR', KEYS[2])
local floor = tonumber(ARGV[3])
if e <= floor then
  e = floor + 1
  redis.call('SET', KEYS[2], e)
end
redis.call('SET', KEYS[1], ARGV[1] .. ' ' .. e, 'PX', ARGV[2])
return e
"""

# KEYS: lease1, epoch1, lease2, epoch2, ... ARGV: node, ttl ms, epoch1, epoch2, ...
# Per room: 1 renewed; 2 taken again (the key was gone, e.g. Redis restarted, and no
# newer epoch was handed out meanwhile, so nobody else can have played it); 0 lost.
RENEW = """
local out = {}
for i = 1, #KEYS, 2 do
  local mine_epoch = ARGV[2 + (i + 1) / 2]
  local mine = ARGV[1] .. ' ' .. mine_epoch
  local current = redis.call('GET', KEYS[i])
  if current == mine then
    redis.call('PEXPIRE', KEYS[i], ARGV[2])
    out[#out + 1] = 1
  elseif not current then
    local e = tonumber(redis.call('GET', KEYS[i + 1]) or '0')
    if e <= tonumber(mine_epoch) then
      redis.call('SET', KEYS[i + 1], mine_epoch)
      redis.call('SET', KEYS[i], mine, 'PX', ARGV[2])
      out[#out + 1] = 2
    else
      out[#out + 1] = 0
    end
  else
    out[#out + 1] = 0
  end
end
return out
"""

# KEYS: lease. ARGV: "<node> <epoch>". Delete the lease only if it is still ours.
RELEASE = """
if redis.call('GET', KEYS[1]) == ARGV[1] then return redis.call('DEL', KEYS[1]) end
return 0
"""

# KEYS: lease, epoch. ARGV: "<node> <epoch>" (ours), floor. Our lease moved past `floor` (an
# epoch the store has seen and Redis has forgotten): the new epoch, or 0 if not ours.
RAISE = """
if redis.call('GET', KEYS[1]) ~= ARGV[1] then return 0 end
local current = tonumber(redis.call('GET', KEYS[2]) or '0')
local e = math.max(current, tonumber(ARGV[2])) + 1
redis.call('SET', KEYS[2], e)
local node = string.match(ARGV[1], '^(%S+)')
redis.call('SET', KEYS[1], node .. ' ' .. e, 'KEEPTTL')
return e
"""

# KEYS: load, nodes. ARGV: the prefix of presence keys. The least loaded live node (one
# whose presence key exists), counted one room busier at once, so a burst of creations
# spreads before the next heartbeats correct the counts. (Key names built here: one Redis.)
PLACE = """
local best, best_load = nil, nil
for _, node in ipairs(redis.call('SMEMBERS', KEYS[2])) do
  if redis.call('EXISTS', ARGV[1] .. node) == 1 then
    local load = tonumber(redis.call('ZSCORE', KEYS[1], node) or '0')
    if best == nil or load < best_load or (load == best_load and node < best) then
      best, best_load = node, load
    end
  end
end
if best == nil then return nil end
redis.call('ZINCRBY', KEYS[1], 1, best)
return best
"""
