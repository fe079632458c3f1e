"""Two-parameter curves: fold curves and their cusps, Hopf curves and their codimension-2
points, and loci of located points (chains over a loading program)."""
