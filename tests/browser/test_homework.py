"""Exercises and solutions in the browser: folded in the book, opened by their title, absent for students."""

import re

import pytest
from browser_helpers import SITES, Visit, pages


def solution_pages():
    return [p for p in pages("book") if re.search(r'class="[^"]*\bsolution\b', (SITES["book"] / p).read_text())]


@pytest.mark.parametrize("path", solution_pages())
def test_solutions_stay_folded_until_their_title_is_clicked(servers, browser, path):
    visit = Visit(browser, servers["book"], path)
    page = visit.page
    try:
        solutions = page.locator(".solution")
        assert solutions.count() >= 2, f"{path}: expected the chapter's solutions"
        for i in range(solutions.count()):
            body = solutions.nth(i).locator(":scope > :not(.admonition-title)")
            assert body.count() and not any(body.nth(j).is_visible() for j in range(body.count())), \
                f"{path}: solution {i} shows before it is opened"
        first, before = solutions.first, page.url
        first.locator(".admonition-title a").first.click()  # the title's link to the exercise
        page.wait_for_timeout(400)
        assert page.url == before, "clicking a solution's title jumped away"
        assert first.locator(":scope > :not(.admonition-title)").first.is_visible(), "the title did not open it"
    finally:
        visit.close()


def test_the_student_site_has_exercises_checks_and_no_solution(servers, browser):
    visit = Visit(browser, servers["student"], "book/03_winding_number.html")
    try:
        page = visit.page
        assert page.locator(".exercise").count() >= 3
        assert page.locator(".solution").count() == 0
        assert page.get_by_text("not written yet").count() >= 2  # the checks ran on the starters
    finally:
        visit.close()


def test_the_book_says_which_launch_buttons_there_are(servers, browser):
    for site, expected in (("book", True), ("student", False)):
        visit = Visit(browser, servers[site], "book/03_winding_number.html")
        try:
            launch = visit.page.locator("a[href*='mybinder.org'], a[href*='colab.research']").count()
            assert bool(launch) == expected, (site, launch)
        finally:
            visit.close()


def test_pages_of_both_sites_match():
    assert [p for p in pages("student")] == [p for p in pages("book")]
    assert all((SITES["student"] / p).exists() for p in pages("book"))
