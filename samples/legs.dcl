/* A walker's frame on four legs: the leg linkage of samples/leg.dcl included four times (an
   extension of the format: `include`, docs/format.md). Each copy's bodies are named after it
   (front_left.crank, ...) and its joints to its own world stand on the chassis. The back legs are
   the same leg turned half a turn about y, so they face backwards. Each copy is flexible: it
   keeps its own degree of freedom, four in all, and a drag of one leg leaves the others still.
   Add `rigid` to an include and that leg is one body, welded as drawn: it no longer moves.

   Try:  dispcon check samples/legs.dcl
         dispcon drag samples/legs.dcl --body front_left.crank --to 0 0 1 --rotation 0 0 3 --steps 30 */

object chassis; fixed; end

include "leg.dcl" as front_left  on chassis position 0 0 1;
include "leg.dcl" as front_right on chassis position 0 0 -1;
include "leg.dcl" as back_left   on chassis position 6 0 1  rotation 0 3.141592653589793 0;
include "leg.dcl" as back_right  on chassis position 6 0 -1 rotation 0 3.141592653589793 0;
