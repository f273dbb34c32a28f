"""compiler/lint"""
