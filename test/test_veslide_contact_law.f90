!> The contact law (veslide_contact_law): the hard wall's per-cell maps, the field procedures
!> that choose the law once per call, and its residual measures as the one definition states them
module test_veslide_contact_law
    use veslide_kinds, only: dp
    use veslide_contact_law, only: contact_law_t, law_id, law_names, law_count, LAW_HARD_WALL, hard_wall_project, &
                                   hard_wall_in_contact, hard_wall_in_contact_shifted, hard_wall_below, &
                                   hard_wall_penetrates
    use testsuite, only: error_t, unittest_t, new_unittest, check
    implicit none
    private
    public :: collect_contact_law

contains

    subroutine collect_contact_law(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("names-and-the-default-law", test_names), &
            new_unittest("hard-wall-maps", test_maps), &
            new_unittest("fields-take-the-maps", test_fields), &
            new_unittest("measures-of-the-hard-wall", test_measures) &
            ]
    end subroutine collect_contact_law

    subroutine test_names(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_law_t) :: law
        call check(error, law%kind == LAW_HARD_WALL .and. law%name() == 'hard_wall', "the default is not the hard wall")
        if (allocated(error)) return
        call check(error, law_id('hard_wall') == LAW_HARD_WALL .and. law_id('sticky') == 0 .and. &
                   size(law_names) == law_count, "law names")
    end subroutine test_names

    !> p >= 0, g >= 0, p g = 0, contact where p > 0: the projection, the contact, the two bounds
    subroutine test_maps(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: v(5) = [-2.0_dp, -tiny(1.0_dp), 0.0_dp, tiny(1.0_dp), 3.0_dp]
        call check(error, all(hard_wall_project(v) == [0.0_dp, 0.0_dp, 0.0_dp, tiny(1.0_dp), 3.0_dp]), "project")
        if (allocated(error)) return
        call check(error, all(hard_wall_in_contact(v) .eqv. [.false., .false., .false., .true., .true.]), "in contact")
        if (allocated(error)) return
        call check(error, all(hard_wall_below(v) .eqv. [.true., .true., .false., .false., .false.]), "below")
        if (allocated(error)) return
        call check(error, all(hard_wall_penetrates(v) .eqv. [.true., .true., .false., .false., .false.]), "penetrates")
        if (allocated(error)) return
        ! contact after a shift c: where project(v - c) > 0, decided without forming v - c
        call check(error, all(hard_wall_in_contact_shifted(v, 1.0_dp) .eqv. &
                              hard_wall_in_contact(hard_wall_project(v - 1.0_dp))) .and. &
                   all(hard_wall_in_contact_shifted(v, -huge(1.0_dp)) .eqv. v > -huge(1.0_dp)), "in contact shifted")
    end subroutine test_maps

    subroutine test_fields(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_law_t) :: law
        real(dp) :: p(7, 5)
        call random_number(p); p = p - 0.4_dp
        p(1, 1) = 0.0_dp
        call check(error, all(law%contact(p) .eqv. (p > 0.0_dp)), "contact cells"); if (allocated(error)) return
        call check(error, all(law%project(p) == max(p, 0.0_dp)), "projected field")
    end subroutine test_fields

    !> penetration max(-g)/h_s, complementarity |sum p g|/(sum p h_s), negative pressure
    !> max(-p)/p_mean (veslide_contact)
    subroutine test_measures(error)
        type(error_t), allocatable, intent(out) :: error
        type(contact_law_t) :: law
        real(dp) :: m(3)
        m = law%measures(-2.0e-9_dp, -3.0e-6_dp, 4.0e3_dp, -5.0_dp, 1.0e-6_dp, 1.0e3_dp)
        call check(error, m(1), 2.0e-9_dp/1.0e-6_dp, "penetration", rel=1.0e-15_dp); if (allocated(error)) return
        call check(error, m(2), 3.0e-6_dp/(4.0e3_dp*1.0e-6_dp), "complementarity", rel=1.0e-15_dp)
        if (allocated(error)) return
        call check(error, m(3), 5.0_dp/1.0e3_dp, "negative pressure", rel=1.0e-15_dp); if (allocated(error)) return
        m = law%measures(1.0e-9_dp, 0.0_dp, 4.0e3_dp, 2.0_dp, 1.0e-6_dp, 1.0e3_dp)
        call check(error, all(m == 0.0_dp), "an admissible candidate has measures of zero")
    end subroutine test_measures

end module test_veslide_contact_law
