"""Whole bifurcation diagrams: recursive branch switching, each branch once, deflation."""
