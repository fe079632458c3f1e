"""Numerics under every curve: dense and sparse factorizations of the bordered systems,
the cubic Hermite arc of a step, second derivatives by differences, typical sizes."""
