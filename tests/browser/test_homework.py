"""Exercises in the browser: checks on the student site, and no solution there.

(That the book's solutions are folded until their title is clicked, and that only the book's
chapters have launch buttons, is checked on every page by test_site.py.)
"""

import re

from browser_helpers import SITES, Visit, pages


def test_every_chapter_of_the_book_has_folded_solutions():
    chapters = [p for p in pages("book") if re.match(r"book/\d\d_", p)]
    assert len(chapters) >= 9, chapters
    for path in chapters:
        html = (SITES["book"] / path).read_text()
        assert len(re.findall(r'class="[^"]*\bsolution\b[^"]*\bdropdown\b', html)) >= 2, path


def test_the_student_site_has_exercises_checks_and_no_solution(servers, browser):
    visit = Visit(browser, servers["student"], "book/03_winding_number.html")
    try:
        page = visit.page
        assert page.locator(".exercise").count() >= 3
        assert page.locator(".solution").count() == 0
        todo = page.locator("pre", has_text="to do, not written yet")  # the checks ran on the starters
        assert todo.count() >= 2
        for k in range(todo.count()):  # a neutral "to do", not a red error
            text, colour = todo.nth(k).evaluate("e => [e.textContent, getComputedStyle(e).color]")
            assert text.startswith("☐") and "✗" not in text and colour == "rgb(66, 74, 83)", (text, colour)
        # where to run it, in the exercise's own words and the intro's
        assert page.get_by_text("run this cell again").count() >= 2
    finally:
        visit.close()


def test_pages_of_both_sites_match():
    assert [p for p in pages("student")] == [p for p in pages("book")]
    assert all((SITES["student"] / p).exists() for p in pages("book"))
