#!/bin/sh
# run.sh — the room (paper figure 3's kind of scene): N pass pairs in
# parallel (xargs -P), averaged. Settings as in examples/passes.sh.
here=$(cd "$(dirname "$0")" && pwd)
exec sh "$here/../passes.sh" "$here/room.pms" room
