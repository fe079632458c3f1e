"""loci"""
